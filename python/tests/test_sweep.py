"""machdyn.sweep: the CLI's designs and table, bit for bit, on any number of threads."""
import numpy as np
import pandas as pd
import pytest

import machdyn
from conftest import example, run_cli

VARY = {"c1.stiffness": "1e4:4e4:4", "I3.inertia": [0.2, 0.3]}
VARY_CLI = ["--vary", "c1.stiffness=1e4:4e4:4", "--vary", "I3.inertia=0.2,0.3"]


def test_grid_table_is_the_clis_byte_for_byte(tmp):
    path = example("hoist-3mass.yaml")
    run_cli("sweep", path, *VARY_CLI, "-o", tmp / "cli", "--jobs", 2)
    df = machdyn.sweep(machdyn.load(path), vary=VARY, threads=2, out=tmp / "py")
    assert (tmp / "py" / "sweep.csv").read_bytes() == (tmp / "cli" / "sweep.csv").read_bytes()
    assert len(df) == 8 and (df["status"] == "ok").all()
    # Grid order: the first axis slowest.
    assert list(df["c1.stiffness"]) == [1e4, 1e4, 2e4, 2e4, 3e4, 3e4, 4e4, 4e4]


def test_one_thread_and_two_give_the_same_frame():
    m = machdyn.load(example("hoist-3mass.yaml"))
    a = machdyn.sweep(m, vary=VARY, threads=1)
    b = machdyn.sweep(m, vary=VARY, threads=2)
    pd.testing.assert_frame_equal(a, b)


def test_each_row_equals_a_single_simulation():
    m = machdyn.load(example("hoist-3mass.yaml"))
    df = machdyn.sweep(m, vary={"c1.stiffness": [2e4, 3e4]}, threads=2)
    for _, row in df.iterrows():
        r = machdyn.simulate(m.with_set({"c1.stiffness": row["c1.stiffness"]}))
        assert row["c1.max_N_m"] == r.summary["links"]["c1"]["max"]


def test_lhs_and_cases_equal_the_cli(tmp):
    path = example("hoist-modes.yaml")
    m = machdyn.load(path)
    cases = m.cases[:2]
    run_cli("sweep", path, "--vary", "c1.stiffness=1e4:4e4", "--method", "lhs", "--samples", 3, "--seed", 7,
            *sum((["--case", c] for c in cases), []), "-o", tmp / "cli", "--jobs", 2)
    df = machdyn.sweep(m, vary={"c1.stiffness": "1e4:4e4"}, method="lhs", samples=3, seed=7, cases=cases,
                       threads=2, out=tmp / "py")
    assert (tmp / "py" / "sweep.csv").read_bytes() == (tmp / "cli" / "sweep.csv").read_bytes()
    assert list(df["case"]) == [cases[0]] * 3 + [cases[1]] * 3


def test_a_failing_run_is_a_row_not_an_exception():
    m = machdyn.load(example("hoist-3mass.yaml"))
    df = machdyn.sweep(m, vary={"c1.stiffness": [2e4, -1]}, threads=1)
    assert list(df["status"]) == ["ok", "error"]
    assert np.isnan(df["c1.max_N_m"].iloc[1])


def test_sweep_of_a_model_from_a_string():
    text = open(example("hoist-3mass.yaml")).read()
    a = machdyn.sweep(machdyn.loads(text), vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    b = machdyn.sweep(machdyn.load(example("hoist-3mass.yaml")), vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    pd.testing.assert_frame_equal(a.drop(columns=["steps", "rejected_steps", "rhs_evals"], errors="ignore"),
                                  b.drop(columns=["steps", "rejected_steps", "rhs_evals"], errors="ignore"))


def test_ctrl_c_stops_a_sweep_and_resume_finishes_the_same_table(tmp):
    import os
    import signal
    import threading
    m = machdyn.load(example("travel-start.yaml"))
    vary = {"adhesion.mu_k": "0.09:0.13:40", "P.value": "6000:7000:50"}  # 2000 runs, ~1 s per thread-core
    threading.Timer(0.15, os.kill, (os.getpid(), signal.SIGINT)).start()
    with pytest.raises(KeyboardInterrupt):
        machdyn.sweep(m, vary=vary, threads=1, out=tmp / "a")
    journaled = len((tmp / "a" / "sweep.journal").read_text().splitlines())
    assert not (tmp / "a" / "sweep.csv").exists()
    df = machdyn.sweep(m, vary=vary, threads=2, out=tmp / "a", resume=True)
    assert len(df) == 2000 and df.attrs["total"] == 2000 and journaled < 2000
    machdyn.sweep(m, vary=vary, threads=2, out=tmp / "b")
    assert (tmp / "a" / "sweep.csv").read_bytes() == (tmp / "b" / "sweep.csv").read_bytes()


def test_sweep_runs_the_loaded_model_not_the_file_as_it_is_now(tmp):
    """A sweep of a model object sweeps what was loaded: after the file is edited the table is the
    one of the loaded text (equal to a sweep of that text), and after it is deleted it still runs."""
    text = open(example("hoist-3mass.yaml"), encoding="utf-8").read()
    path = tmp / "model.yaml"
    path.write_text(text, encoding="utf-8")
    m = machdyn.load(path)
    before = machdyn.sweep(m, vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    # Another model in the same file: a sweep of the file as it is now is refused (no link c1).
    path.write_text(text.replace("c1:", "c1_renamed:"), encoding="utf-8")
    after_edit = machdyn.sweep(m, vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    pd.testing.assert_frame_equal(before, after_edit)
    path.unlink()
    after_delete = machdyn.sweep(m, vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    pd.testing.assert_frame_equal(before, after_delete)
    # Independent answer: the same text loaded from a string.
    from_text = machdyn.sweep(machdyn.loads(text, source=str(path)), vary={"c1.stiffness": [2e4, 3e4]}, threads=1)
    pd.testing.assert_frame_equal(before, from_text)
