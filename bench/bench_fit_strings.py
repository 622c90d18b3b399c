"""`gearhead fit` of a log whose every record is a kept signal: figures only, never asserted.

A SysId routine logged alone, at a fast loop, for hours: every loop writes the test state (a string,
as WPILib's SysIdRoutineLog logs it on every loop of the routine), the voltage, the position and the
velocity, so every record of the file is one the fit reads and a quarter of them are strings (167 MB,
2.6 million loops by default). Written once per run with WPILib's own DataLogWriter
(robotpy's wpiutil, the test extra), in a temporary folder (or --keep DIR, reused when there).

Measured, each in a fresh process: `gearhead fit LOG --card elevator --json` (wall time and peak
resident memory: the process is the only child of a small parent of its own, whose
RUSAGE_CHILDREN peak is then that process's), and the reader alone (core.fit.logs.read_wpilog of the
four signals, every one kept) with its peak resident memory. With --other PYTHON, the same
figures from another checkout's venv (its editable install imports that checkout), run in turns
with this one: the machine's load cancels out of the ratios. The fits of both must be equal.

    .venv/bin/python bench/bench_fit_strings.py [--loops N] [--runs N] [--keep DIR] [--other PYTHON]
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_fit import plant_substeps  # noqa: E402  bench_fit.py's elevator


def _arg(name: str, default=None):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


LOOPS = int(_arg("--loops", 2_600_000))
RUNS = int(_arg("--runs", 3))
KEEP = _arg("--keep")
OTHER = _arg("--other")
LOOP = 0.005  # s: a 200 Hz routine
SEED = 45
# a cycle of the four tests, repeated over the log: (state, start s in the cycle, length s, volts(s))
CYCLE = 40.0
TESTS = (
    ("quasistatic-forward", 2.0, 6.0, lambda s: 1.0 * s),
    ("quasistatic-reverse", 12.0, 6.0, lambda s: -1.0 * s),
    ("dynamic-forward", 22.0, 2.0, lambda s: 7.0),
    ("dynamic-reverse", 30.0, 2.0, lambda s: -7.0),
)


def _cycle(rng) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """One cycle's loops: (state, volts, position m, velocity m/s), the plant integrated exactly
    over 0.5 ms substeps with the voltage held for each loop, at rest between tests."""
    n = int(round(CYCLE / LOOP))
    state, u_, q_, v_ = ["none"] * n, np.zeros(n), np.zeros(n), np.zeros(n)
    q = 0.0
    for name, start, length, volts in TESTS:
        v = 0.0
        k0 = int(round(start / LOOP))
        for k in range(k0, k0 + int(round(length / LOOP))):
            u = volts((k - k0) * LOOP)
            state[k], u_[k], q_[k], v_[k] = name, u, q, v
            q, v = plant_substeps(q, v, u, LOOP / 10, 10)
        q_[k0 + int(round(length / LOOP)) :] = q
    q_ += rng.normal(0, 1e-4, n)
    v_ += rng.normal(0, 1e-3, n)
    return state, u_, q_, v_


def write_log(path: Path, loops: int) -> dict:
    import wpiutil
    from wpiutil import log as wl

    rng = np.random.default_rng(SEED)
    state, u, q, v = _cycle(rng)
    n = len(state)
    w = wpiutil.DataLogWriter(str(path), "SysId")
    mech = "elevator"
    st = wl.StringLogEntry(w, f"sysid-test-state-{mech}", "", 1)
    volts = wl.DoubleLogEntry(w, f"voltage-lift-{mech}", "Volt", 1)
    pos = wl.DoubleLogEntry(w, f"position-lift-{mech}", "Meter", 1)
    vel = wl.DoubleLogEntry(w, f"velocity-lift-{mech}", "Meter per Second", 1)
    u, q, v = u.tolist(), q.tolist(), v.tolist()
    for k in range(loops):
        ts = 1_000_000 + 5000 * k
        j = k % n
        st.append(state[j], ts)
        volts.append(u[j], ts + 1)
        pos.append(q[j], ts + 2)
        vel.append(v[j], ts + 3)
        if k % 1000 == 0:
            w.flush()  # DataLogWriter blocks once its buffers fill until they are written
    w.flush()
    w.stop()
    del w
    return {"bytes": path.stat().st_size, "records": 4 * loops}


PEAK = """
import resource, subprocess, sys, time
t0 = time.perf_counter()
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
wall = time.perf_counter() - t0
if done.returncode:
    sys.exit(done.stdout + done.stderr)
use = resource.getrusage(resource.RUSAGE_CHILDREN)
print(wall, use.ru_utime + use.ru_stime, use.ru_maxrss)
print(done.stdout)
"""

READER = """
import resource, sys, time
from gearhead.core.fit import logs
t0, c0 = time.perf_counter(), time.process_time()
sigs, _, _ = logs.read_wpilog(sys.argv[1], lambda n: True)
print(time.perf_counter() - t0, time.process_time() - c0, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


def fit_run(python: str, log: Path) -> tuple[float, float, float, dict]:
    """(wall s, CPU s, peak resident MB, the --json report) of one `gearhead fit` in a fresh process."""
    gearhead = str(Path(python).with_name("gearhead"))
    argv = [gearhead, "fit", str(log), "--card", "elevator", "--json"]
    out = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True)
    if out.returncode:
        sys.exit(f"{' '.join(argv)} failed:\n{out.stdout}{out.stderr}")
    head, _, body = out.stdout.partition("\n")
    wall, cpu, kib = head.split()
    return float(wall), float(cpu), int(kib) / 1024, json.loads(body)


def reader_run(python: str, log: Path) -> tuple[float, float, float]:
    """(wall s, CPU s, peak resident MB) of the reader alone, every signal kept, in a fresh process."""
    out = subprocess.run([python, "-c", READER, str(log)], capture_output=True, text=True, check=True)
    wall, cpu, kib = out.stdout.split()
    return float(wall), float(cpu), int(kib) / 1024


def main() -> None:
    folder = Path(KEEP) if KEEP else Path(tempfile.mkdtemp(prefix="gearhead-fit-strings-"))
    folder.mkdir(parents=True, exist_ok=True)
    log = folder / f"strings-{LOOPS}.wpilog"
    if not log.exists():
        t0 = time.perf_counter()
        info = write_log(log, LOOPS)
        print(
            f"wrote {log}: {info['bytes'] / 1e6:.0f} MB, {info['records']} records "
            f"in {time.perf_counter() - t0:.0f} s"
        )
    else:
        print(f"reusing {log}: {log.stat().st_size / 1e6:.0f} MB")
    pythons = {"this": sys.executable, **({"other": OTHER} if OTHER else {})}
    fits: dict[str, list] = {k: [] for k in pythons}
    reads: dict[str, list] = {k: [] for k in pythons}
    reports = {}
    for _ in range(RUNS):
        for k, py in pythons.items():  # in turns: the load falls on both alike
            *figures, report = fit_run(py, log)
            fits[k].append(figures)
            reports[k] = report
            reads[k].append(reader_run(py, log))

    def med(rows, i):
        return statistics.median(r[i] for r in rows)

    for k in pythons:
        f, r = fits[k], reads[k]
        print(
            f"{k:>5}: gearhead fit {med(f, 0):6.2f} s wall, {med(f, 1):6.2f} s CPU, peak RSS {med(f, 2):5.0f} MB;"
            f" reader alone {med(r, 0):6.2f} s wall, {med(r, 1):6.2f} s CPU, peak RSS {med(r, 2):5.0f} MB"
            f"  (medians of {RUNS})"
        )
    if OTHER:
        for what, rows in (("gearhead fit", fits), ("reader", reads)):
            t, o = rows["this"], rows["other"]
            print(
                f"this/other, {what}: wall {med(t, 0) / med(o, 0):.3f}, CPU {med(t, 1) / med(o, 1):.3f},"
                f" peak memory {med(t, 2) / med(o, 2):.3f}"
            )
        same = reports["this"] == reports["other"]
        print("fit reports equal:", same)
        if not same:
            for key in reports["this"]:
                if reports["this"].get(key) != reports["other"].get(key):
                    print(f"  differs: {key}")
    fav = reports["this"].get("favoured")
    print(
        "favoured:",
        fav,
        json.dumps(reports["this"].get("fits", {}).get(fav, {}).get("gains"), sort_keys=True),
    )


if __name__ == "__main__":
    main()
