"""The Python API and the wheel's command as cluster and Python users use
them to scale out, and what a study given to them cannot do. Runs against the installed
wheel (scripts/test_wheel.sh)."""

import os
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

import batstudy

BATSTUDY = shutil.which("batstudy", path=os.path.dirname(sys.executable)) or "batstudy"

STUDY = {
    "name": "scaleout",
    "model": "rigid",
    "base": {"ball": {"speed": 40}},
    "grid": {"swing.omega": [0, -40], "impact.z": {"range": [0.45, 0.80, 0.05]}},
}
STUDY_YAML = """name: scaleout
model: rigid
base: {ball: {speed: 40}}
grid:
  swing.omega: [0, -40]
  impact.z: {range: [0.45, 0.80, 0.05]}
"""


def exit_speeds(path) -> np.ndarray:
    with h5py.File(path, "r") as f:
        return f["summary/exit_speed"][()]


def test_run_takes_a_path_yaml_text_or_a_dict_and_shards_merge_to_the_whole(tmp_path):
    study_file = tmp_path / "s.yaml"
    study_file.write_text(STUDY_YAML)
    whole = batstudy.run(study_file, output=tmp_path / "whole.h5", progress=False)
    from_text = batstudy.run(STUDY_YAML, output=tmp_path / "text.h5", progress=False)
    # any pair of whole numbers: a tuple, a list (a scheduler's [task, tasks]), NumPy's
    shards = [
        batstudy.run(STUDY, output=tmp_path / f"part{i}.h5", shard=pair, progress=False)
        for i, pair in ((1, (1, 3)), (2, [2, 3]), (3, np.array([3, 3])))
    ]
    merged = batstudy.merge(tmp_path / "merged.h5", shards)
    for other in (from_text, merged):
        np.testing.assert_array_equal(exit_speeds(other), exit_speeds(whole))
    # an incomplete set is refused, naming the shard, and nothing is written
    with pytest.raises(batstudy.StudyError, match="lack"):
        batstudy.merge(tmp_path / "partial.h5", shards[:2])
    assert not (tmp_path / "partial.h5").exists()
    for bad in ((0,), (1.5, 3), (True, 2), "1/3"):
        with pytest.raises(TypeError):
            batstudy.run(STUDY, shard=bad, progress=False)
    with pytest.raises(batstudy.StudyError, match="shard"):
        batstudy.run(STUDY, output=tmp_path / "x.h5", shard=(4, 3), progress=False)


def test_plan_and_validate_say_what_a_study_is_without_running_it(tmp_path):
    p = batstudy.plan(STUDY)
    assert p["name"] == "scaleout" and p["points"] == 16
    assert p["dims"] == [("swing_omega", 2), ("impact_z", 8)]
    assert batstudy.validate(STUDY_YAML) is None
    with pytest.raises(batstudy.StudyError, match="speedd"):
        batstudy.validate({"name": "bad", "base": {"ball": {"speedd": 3}}})


def test_slurm_from_the_wheel_runs_the_installed_command(tmp_path):
    """The array script's command line is the installed `batstudy` (not the Python
    interpreter, which the native module sees as its executable), and it runs a shard."""
    study_file = tmp_path / "s.yaml"
    study_file.write_text(STUDY_YAML)
    for command, words in (
        ([BATSTUDY], [os.path.abspath(BATSTUDY)]),
        ([sys.executable, "-m", "batstudy"], [sys.executable, "-m", "batstudy"]),
    ):
        jobs = tmp_path / f"jobs{len(words)}"
        r = subprocess.run([*command, "slurm", str(study_file), "--shards", "2", "--dir", str(jobs)],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        array = (jobs / "array.sbatch").read_text()
        assert f"BATSTUDY=({' '.join(words)})" in array, array
        env = {**os.environ, "SLURM_ARRAY_TASK_ID": "2", "SLURM_CPUS_PER_TASK": "1"}
        r = subprocess.run(["bash", str(jobs / "array.sbatch")], cwd=jobs, env=env, capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr
        shard = jobs / "scaleout.shard-2-of-2.h5"
        with h5py.File(shard, "r") as f:
            assert f.attrs["shard"] == "2/2"


def test_a_bare_carriage_return_cannot_lift_keys_out_of_the_spec():
    """A bare \\r is a line break to YAML: it let top-level keys (allow_implausible) escape
    the `base:` wrapper that simulate() puts around the spec."""
    spec = "ball: {speed: 40}\rallow_implausible: true\rbat: {material: {density: 50000}}"
    for sep in ("\r", "\u2028", "\x85"):
        with pytest.raises(batstudy.StudyError):
            batstudy.simulate(spec.replace("\r", sep))


def test_a_history_too_big_for_memory_raises_instead_of_killing_the_process():
    big = {"fields": ["force", "displacement"], "interval": 1e-9, "duration": 3e-3, "z_step": 0.001}
    with pytest.raises(batstudy.StudyError, match="MiB per point"):
        batstudy.simulate({"impact": {"z": 0.7}}, history=big)
    with pytest.raises(batstudy.StudyError, match="twice"):
        batstudy.simulate({"impact": {"z": 0.7}}, history={"fields": ["force", "force"]})


def test_mutated_spec_texts_raise_study_errors_and_never_crash():
    """A bounded, seeded mutation fuzz of simulate()'s text: whatever the text,
    the call returns a result or raises StudyError; it never aborts the interpreter (a
    crash would end this test run) or raises anything else."""
    import random

    rng = random.Random(0x5EED)
    seeds = [
        "bat: {preset: aluminum}\nball: {speed: 40}\nimpact: {z: 0.7}\nmodel: rigid\n",
        "impact: {z: 0.65}\nswing: {omega: -30}\nmodel: rigid\nball: {law: {kind: elastic}}\n",
    ]
    tokens = ["\r", "\u2028", "\x85", "\n", ": ", "- ", "{", "}", "[", "]", "'", '"', "#", ".nan", "-1",
              "1e400", "allow_implausible: true", "base:", "history:", "name: x", "\t", "\x00", "&a", "*a"]
    outcomes = {"ok": 0, "refused": 0}
    for k in range(300):
        text = list(rng.choice(seeds))
        for _ in range(rng.randint(1, 2)):
            at = rng.randrange(len(text) + 1)
            if rng.random() < 0.7:
                text[at:at] = list(rng.choice(tokens))
            elif text:
                del text[at:at + rng.randint(1, 6)]
        spec = "".join(text)
        try:
            r = batstudy.simulate(spec)
            assert np.isfinite(r["exit_speed"]), (k, spec)
            outcomes["ok"] += 1
        except batstudy.StudyError as e:
            assert str(e), (k, spec)
            outcomes["refused"] += 1
    # both paths exercised (most mutations break a spec; some leave it valid)
    assert outcomes["ok"] >= 5 and outcomes["refused"] >= 100, outcomes


# A wave-model study whose shards take some seconds on one thread (about 5 s on an idle 2-core
# machine with the release wheel), several times what the time-out below leaves each start:
# a shard that finished before its signal would test no requeue.
LONG_STUDY = {
    "name": "long",
    "model": "wave",
    "base": {"ball": {"speed": 40}},
    "grid": {"swing.omega": {"range": [-50, 0, 1]}, "impact.z": {"range": [0.40, 0.84, 0.0004]}},
}


def test_submitit_requeues_a_timed_out_shard_which_resumes_to_the_whole(tmp_path):
    """The submitit recipe: a `ShardTask` job that times out (the local executor signals it
    1.2 s after each start, as Slurm signals a job before its time limit) is checkpointed and
    requeued, and each requeued job resumes the shard: the merged shards equal one run, bit
    for bit."""
    submitit = pytest.importorskip("submitit")

    ex = submitit.LocalExecutor(folder=tmp_path / "logs", max_num_timeout=20)
    ex.update_parameters(timeout_min=0.2, signal_delay_s=10.8)
    job = ex.submit(batstudy.ShardTask(LONG_STUDY, (1, 2), tmp_path / "s1.h5", jobs=1))
    parts = [job.result(), batstudy.ShardTask(LONG_STUDY, (2, 2), tmp_path / "s2.h5", jobs=1)()]
    log = job.stdout() or ""
    assert "timed-out" in log and "Requeued job" in log, log
    whole = batstudy.run(LONG_STUDY, output=tmp_path / "whole.h5", progress=False)
    merged = batstudy.merge(tmp_path / "merged.h5", parts)
    np.testing.assert_array_equal(exit_speeds(merged), exit_speeds(whole))


def test_dask_runs_one_shard_per_worker_at_a_time(tmp_path):
    """The dask recipe: workers that each offer one `shard` resource, tasks that each need
    it: no worker runs two shards at once (each shard's run uses the worker's cores), and the
    merged shards equal one run."""
    distributed = pytest.importorskip("distributed")
    import time

    def timed(task):
        start = time.time()
        path = task()
        return path, distributed.get_worker().address, start, time.time()

    n = 4
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=2, processes=True, resources={"shard": 1}, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        futures = [
            client.submit(timed, batstudy.ShardTask(STUDY, (i, n), tmp_path / f"d{i}.h5", jobs=1),
                          resources={"shard": 1}, pure=False)
            for i in range(1, n + 1)
        ]
        done = client.gather(futures)
    by_worker = {}
    for _, worker, start, end in done:
        by_worker.setdefault(worker, []).append((start, end))
    for spans in by_worker.values():
        spans.sort()
        for (s0, e0), (s1, e1) in zip(spans, spans[1:]):
            assert s1 >= e0, f"two shards at once on one worker: {spans}"
    whole = batstudy.run(STUDY, output=tmp_path / "whole.h5", progress=False)
    merged = batstudy.merge(tmp_path / "merged.h5", [p for p, *_ in done])
    np.testing.assert_array_equal(exit_speeds(merged), exit_speeds(whole))
