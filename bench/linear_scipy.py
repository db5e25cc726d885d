"""scipy on the matrices bench_linear wrote (issue 12): the same analyses, timed and compared.

    python3 bench/linear_scipy.py DIR [REPEATS]

- 1000-mass chain: scipy.linalg.eigh(K, M) (all eigenpairs, dense LAPACK) and eigh_tridiagonal of
  M^-1/2 K M^-1/2 (the structure machdyn exploits) against machdyn's undamped_modes; the largest
  relative difference of the 999 elastic frequencies.
- 100-/300-mass chains: scipy.linalg.eig of the state-space matrix [0 I; -M^-1 K  -M^-1 D].
- 100-mass chain FRF at 1000 frequencies: a dense complex solve per frequency (numpy.linalg.solve)
  and scipy.signal.freqresp of the state-space system, against machdyn's H.
"""
import sys
import time
import warnings

import numpy as np
import scipy.linalg as la
import scipy.signal as sig


def best_of(repeats, f):
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        best = min(best, time.perf_counter() - t0)
    return best, out


def load(d, n):
    M = np.loadtxt(f"{d}/chain{n}_M.txt")
    K = np.loadtxt(f"{d}/chain{n}_K.txt")
    D = np.loadtxt(f"{d}/chain{n}_D.txt")
    return M, K, D


def state_space(M, K, D):
    n = len(M)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -K / M[:, None]
    A[n:, n:] = -D / M[:, None]
    return A


def main():
    d = sys.argv[1]
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    M, K, D = load(d, 1000)
    t, (lam, _) = best_of(repeats, lambda: la.eigh(K, np.diag(M)))
    w = np.sqrt(lam[1:])  # one rigid-body mode
    ours = np.loadtxt(f"{d}/chain1000_omega.txt")
    print(f"chain 1000: scipy eigh(K, M) {t * 1e3:.1f} ms; max rel. difference of the 999 frequencies "
          f"{np.max(np.abs(w - ours) / ours):.2e}")

    # The same structure machdyn uses: the symmetric tridiagonal M^-1/2 K M^-1/2 (LAPACK stemr).
    s = 1.0 / np.sqrt(M)
    dg, off = np.diag(K) * s * s, np.diag(K, -1) * s[1:] * s[:-1]
    t, (lam, _) = best_of(repeats, lambda: la.eigh_tridiagonal(dg, off))
    w = np.sqrt(np.maximum(lam[1:], 0))
    print(f"chain 1000: scipy eigh_tridiagonal {t * 1e3:.1f} ms; max rel. difference {np.max(np.abs(w - ours) / ours):.2e}")

    for n in (100, 300):
        M, K, D = load(d, n)
        A = state_space(M, K, D)
        t, lam = best_of(max(1, repeats // (5 if n > 100 else 1)), lambda: la.eigvals(A))
        osc = np.sort_complex(lam[(lam.imag > 0) & (np.abs(lam) > 1e-7 * np.abs(lam).max())])
        ours = np.loadtxt(f"{d}/chain{n}_damped.txt")
        ours = np.sort_complex(ours[:, 0] + 1j * ours[:, 1])
        ours = ours[ours.imag > 0]
        osc = osc[np.argsort(np.abs(osc))]
        ours = ours[np.argsort(np.abs(ours))]
        diff = np.max(np.abs(osc - ours) / np.abs(ours)) if len(osc) == len(ours) else float("nan")
        print(f"chain {n}: scipy eig of the {2 * n}x{2 * n} state space {t * 1e3:.1f} ms; "
              f"max rel. difference of the eigenvalues {diff:.2e}")

    M, K, D = load(d, 100)
    frf = np.loadtxt(f"{d}/chain100_frf.txt")
    w, H = frf[:, 0], frf[:, 1] + 1j * frf[:, 2]
    cq, cv = np.loadtxt(f"{d}/chain100_out.txt").T
    b = np.zeros(len(M))
    b[0] = 1.0
    Mm = np.diag(M)

    def direct():
        return np.array([(cq + 1j * x * cv) @ np.linalg.solve(K - x * x * Mm + 1j * x * D, b) for x in w])

    t, Hs = best_of(repeats, direct)
    print(f"chain 100: numpy dense solve at 1000 frequencies {t * 1e3:.1f} ms; "
          f"max rel. difference {np.max(np.abs(Hs - H) / np.abs(H)):.2e}")
    n = len(M)
    A = state_space(M, K, D)
    B = np.zeros((2 * n, 1))
    B[n, 0] = 1.0 / M[0]
    C = np.concatenate([cq, cv])[None, :]
    # freqresp converts the state space to zeros, poles and gain through a transfer function, whose
    # polynomial coefficients over- or underflow for a 200-state system.
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t, (_, Hf) = best_of(1, lambda: sig.freqresp(sig.StateSpace(A, B, C, np.zeros((1, 1))), w))
        print(f"chain 100: scipy.signal.freqresp (state space) at 1000 frequencies {t * 1e3:.1f} ms; "
              f"max rel. difference {np.max(np.abs(Hf - H) / np.abs(H)):.2e}")
    except (np.linalg.LinAlgError, ValueError) as e:
        print(f"chain 100: scipy.signal.freqresp (state space) fails: {type(e).__name__}: {e}")


if __name__ == "__main__":
    main()
