#include "cvode_bdf.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"

namespace machdyn {

struct CvodeBdf::Impl {
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr, dky = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  OdeSystem* sys = nullptr;
  bool initialized = false;
  bool finite = true;
  bool sparse = false;               // KLU on the system's sparse Jacobian
  Eigen::SparseMatrix<double> Js;    // its last evaluation
  int bad_component = -1;
};

namespace {

int rhs_cb(realtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* impl = static_cast<CvodeBdf::Impl*>(user);
  const double* yy = N_VGetArrayPointer(y);
  double* dd = N_VGetArrayPointer(ydot);
  impl->sys->rhs(t, yy, dd);
  const int n = impl->sys->size();
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(dd[i])) {
      impl->bad_component = i;
      return 1;  // recoverable: CVODE retries with a smaller step
    }
  return 0;
}

int jac_cb(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  auto* impl = static_cast<CvodeBdf::Impl*>(user);
  const int n = impl->sys->size();
  // SUNDIALS dense matrices are column-major, like Eigen's default.
  Eigen::Map<Eigen::MatrixXd> JJ(SM_DATA_D(J), n, n);
  impl->sys->jacobian(t, N_VGetArrayPointer(y), JJ);
  return 0;
}

int sparse_jac_cb(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  auto* impl = static_cast<CvodeBdf::Impl*>(user);
  impl->sys->sparse_jacobian(t, N_VGetArrayPointer(y), impl->Js);
  const auto& A = impl->Js;
  if (A.nonZeros() > SM_NNZ_S(J)) return -1;  // the pattern grew: not allowed
  const auto n = A.outerSize();
  for (Eigen::Index c = 0; c <= n; ++c) SM_INDEXPTRS_S(J)[c] = static_cast<sunindextype>(A.outerIndexPtr()[c]);
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
    SM_INDEXVALS_S(J)[k] = static_cast<sunindextype>(A.innerIndexPtr()[k]);
    SM_DATA_S(J)[k] = A.valuePtr()[k];
  }
  return 0;
}

}  // namespace

CvodeBdf::CvodeBdf(OdeSystem& system, const StepperOptions& options)
    : impl_(new Impl), sys_(system), opt_(options), y_(static_cast<size_t>(system.size()), 0.0), dy_(y_) {
  const auto n = static_cast<sunindextype>(system.size());
  impl_->sys = &system;
  if (SUNContext_Create(nullptr, &impl_->ctx) != 0) throw std::runtime_error("SUNContext_Create failed");
  impl_->y = N_VNew_Serial(n, impl_->ctx);
  impl_->dky = N_VNew_Serial(n, impl_->ctx);
  // Large systems with a sparse Jacobian: KLU on a compressed-column matrix (O(nonzeros) memory),
  // else the dense direct solver.
  impl_->sparse = system.has_sparse_jacobian() && system.size() >= kSparseFrom;
  if (impl_->sparse) {
    std::vector<double> y0(static_cast<size_t>(system.size()), 0.0);
    system.sparse_jacobian(0.0, y0.data(), impl_->Js);
    impl_->A = SUNSparseMatrix(n, n, std::max<sunindextype>(1, impl_->Js.nonZeros()), CSC_MAT, impl_->ctx);
    impl_->LS = SUNLinSol_KLU(impl_->y, impl_->A, impl_->ctx);
  } else {
    impl_->A = SUNDenseMatrix(n, n, impl_->ctx);
    impl_->LS = SUNLinSol_Dense(impl_->y, impl_->A, impl_->ctx);
  }
  impl_->mem = CVodeCreate(CV_BDF, impl_->ctx);
  if (!impl_->y || !impl_->A || !impl_->LS || !impl_->mem) throw std::runtime_error("CVODE allocation failed");
}

CvodeBdf::~CvodeBdf() {
  CVodeFree(&impl_->mem);
  SUNLinSolFree(impl_->LS);
  SUNMatDestroy(impl_->A);
  N_VDestroy(impl_->y);
  N_VDestroy(impl_->dky);
  SUNContext_Free(&impl_->ctx);
  delete impl_;
}

void CvodeBdf::reset(double t0, const double* y0) {
  std::copy(y0, y0 + sys_.size(), N_VGetArrayPointer(impl_->y));
  std::copy(y0, y0 + sys_.size(), y_.begin());
  sys_.rhs(t0, y_.data(), dy_.data());
  t_ = t_old_ = t0;
  still_ = false;
  if (!impl_->initialized) {
    CVodeInit(impl_->mem, rhs_cb, t0, impl_->y);
    CVodeSetUserData(impl_->mem, impl_);
    CVodeSStolerances(impl_->mem, opt_.rtol, opt_.atol);
    CVodeSetLinearSolver(impl_->mem, impl_->LS, impl_->A);
    if (impl_->sparse)
      CVodeSetJacFn(impl_->mem, sparse_jac_cb);
    else if (sys_.has_jacobian())
      CVodeSetJacFn(impl_->mem, jac_cb);
    CVodeSetMaxNumSteps(impl_->mem, 100000);
    CVodeSetErrHandlerFn(impl_->mem, [](int, const char*, const char*, char*, void*) {}, nullptr);
    if (opt_.h_max > 0) CVodeSetMaxStep(impl_->mem, opt_.h_max);
    impl_->initialized = true;
  } else {
    // CVodeReInit zeroes CVODE's counters: keep what the run took so far (stats() adds them).
    done_ = stats();
    CVodeReInit(impl_->mem, t0, impl_->y);
  }
}

void CvodeBdf::step(double t_limit) {
  if (stats().steps >= opt_.max_steps) {
    // Name the state with the largest weighted local error of the last step (what holds it short).
    std::string element = "integrator";
    N_Vector ele = N_VClone(impl_->y), ewt = N_VClone(impl_->y);
    if (stats().steps > 0 && CVodeGetEstLocalErrors(impl_->mem, ele) == 0 && CVodeGetErrWeights(impl_->mem, ewt) == 0) {
      double worst = -1;
      for (int i = 0; i < sys_.size(); ++i) {
        const double e = std::abs(NV_Ith_S(ele, i) * NV_Ith_S(ewt, i));
        if (!(e <= worst)) worst = e, element = sys_.state_name(i);
      }
    }
    N_VDestroy(ele);
    N_VDestroy(ewt);
    throw SolverError(element, t_, "the maximum number of steps was reached (held short by this state)");
  }
  // A stop time closer to the start than CVODE resolves (CV_TOO_CLOSE below 2 ulps of t: two
  // breakpoints an ulp apart, a table point and a zero crossing computed at it): over that interval
  // the state does not change, so the step goes there without CVODE, which starts again from it.
  still_ = false;
  if (t_limit > t_ && t_limit - t_ <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_), std::abs(t_limit))) {
    t_old_ = t_;
    t_ = t_limit;
    done_ = stats();
    std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(impl_->y));
    CVodeReInit(impl_->mem, t_, impl_->y);
    still_ = true;
    return;
  }
  CVodeSetStopTime(impl_->mem, t_limit);
  double tret = t_;
  impl_->bad_component = -1;
  int flag = CVode(impl_->mem, t_limit, impl_->y, &tret, CV_ONE_STEP);
  if (flag < 0) {
    double tcur = t_;
    CVodeGetCurrentTime(impl_->mem, &tcur);
    std::string element = impl_->bad_component >= 0 ? sys_.state_name(impl_->bad_component) : "integrator";
    if (flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE) {
      // Blame the component with the largest weighted local error.
      N_Vector ele = N_VClone(impl_->y), ewt = N_VClone(impl_->y);
      if (CVodeGetEstLocalErrors(impl_->mem, ele) == 0 && CVodeGetErrWeights(impl_->mem, ewt) == 0 &&
          impl_->bad_component < 0) {
        double worst = -1;
        for (int i = 0; i < sys_.size(); ++i) {
          double e = std::abs(NV_Ith_S(ele, i) * NV_Ith_S(ewt, i));
          if (e > worst) worst = e, element = sys_.state_name(i);
        }
      }
      N_VDestroy(ele);
      N_VDestroy(ewt);
    }
    // CVodeGetReturnFlagName returns a string of malloc's that the caller frees.
    const std::unique_ptr<char, void (*)(void*)> name(CVodeGetReturnFlagName(flag), std::free);
    throw SolverError(element, tcur, fmt::format("CVODE failed: {}", name ? name.get() : "unknown flag"));
  }
  t_old_ = t_;
  t_ = tret;
  std::copy(N_VGetArrayPointer(impl_->y), N_VGetArrayPointer(impl_->y) + sys_.size(), y_.begin());
  sys_.rhs(t_, y_.data(), dy_.data());
}

void CvodeBdf::interpolate(double t, double* y_out) const {
  if (t >= t_ || still_) {
    std::copy(y_.begin(), y_.end(), y_out);
    return;
  }
  CVodeGetDky(impl_->mem, t, 0, impl_->dky);
  std::copy(N_VGetArrayPointer(impl_->dky), N_VGetArrayPointer(impl_->dky) + sys_.size(), y_out);
}

void CvodeBdf::derivative(double t, double* dy_out) const {
  if (still_) {
    std::copy(dy_.begin(), dy_.end(), dy_out);
    return;
  }
  CVodeGetDky(impl_->mem, std::min(t, t_), 1, impl_->dky);
  std::copy(N_VGetArrayPointer(impl_->dky), N_VGetArrayPointer(impl_->dky) + sys_.size(), dy_out);
}

StepperStats CvodeBdf::stats() const {
  StepperStats s = done_;
  if (!impl_->initialized) return s;  // before the first reset() CVODE has no counters yet
  long v = 0;
  CVodeGetNumSteps(impl_->mem, &v);
  s.steps += v;
  CVodeGetNumRhsEvals(impl_->mem, &v);
  s.rhs_evals += v;
  long lsrhs = 0;
  CVodeGetNumLinRhsEvals(impl_->mem, &lsrhs);
  s.rhs_evals += lsrhs;
  CVodeGetNumJacEvals(impl_->mem, &v);
  s.jac_evals += v;
  long ef = 0, cf = 0;
  CVodeGetNumErrTestFails(impl_->mem, &ef);
  CVodeGetNumNonlinSolvConvFails(impl_->mem, &cf);
  s.rejected += ef + cf;
  return s;
}


}  // namespace machdyn
