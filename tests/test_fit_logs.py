"""core.fit.logs (issue 44 item 1): our streaming WPILog reader against robotpy's DataLogReader on the
same files, record by record; bounded memory on a large log; CSV; hostile files refused naming the
file and what is wrong."""

from __future__ import annotations

import math
import struct
import tracemalloc

import numpy as np
import pytest

from gearhead.core.errors import InputError
from gearhead.core.fit import logs

wpiutil = pytest.importorskip("wpiutil")
from wpiutil import log as wlog  # noqa: E402


def _write_mixed(path):
    """A log exercising every width of the record header: 300 entries (2-byte ids), timestamps up to
    2^40 µs (6-byte), a 70 000-byte raw payload (3-byte size), every standard type, metadata set
    again, an entry finished and its id reused, records out of time order."""
    w = wpiutil.DataLogWriter(str(path), "extra header ✓")
    d = wlog.DoubleLogEntry(w, "voltage-m-elev", "Volt", 1)
    s = wlog.StringLogEntry(w, "sysid-test-state-elev", "", 2)
    i = wlog.IntegerLogEntry(w, "int", '{"source":"NT"}', 3)
    fl = wlog.FloatLogEntry(w, "float", "", 3)
    b = wlog.BooleanLogEntry(w, "bool", "", 3)
    da = wlog.DoubleArrayLogEntry(w, "darr", "", 3)
    sa = wlog.StringArrayLogEntry(w, "sarr", "", 3)
    raw = wlog.RawLogEntry(w, "raw", "", 3)
    many = [wlog.DoubleLogEntry(w, f"e{k}", "", 4) for k in range(300)]
    for k in range(50):
        d.append(0.25 * k, 1000 + 20_000 * k)
        s.append("quasistatic-forward" if k < 25 else "dynamic-reverse", 1000 + 20_000 * k)
        i.append(-(k**5), 2**40 - k)
        fl.append(k / 3, 7)
        b.append(k % 2 == 0, 8)
    d.append(-1.5, 5)  # earlier than the rest: the format allows it
    da.append([1.0, 2.5, -3.0], 9)
    sa.append(["a", "bc", ""], 10)
    raw.append(bytes(range(256)) * 275, 11)
    for k, e in enumerate(many):
        e.append(float(k), 12)
    d.setMetadata("Volts", 13)
    many[0].finish(14)
    wlog.DoubleLogEntry(w, "reused", "", 15).append(9.0, 16)
    w.flush()
    w.stop()
    del w


def test_every_record_equals_robotpys(tmp_path):
    path = tmp_path / "mixed.wpilog"
    _write_mixed(path)
    ours = list(logs.WPILog(path).records())
    log = logs.WPILog(path)
    assert log.extra_header == "extra header ✓" and log.version == 0x0100
    count = 0
    for a, b in zip(ours, wlog.DataLogReader(str(path)), strict=True):  # its records live while iterated
        count += 1
        assert (a.entry, a.timestamp, len(a.payload)) == (b.getEntry(), b.getTimestamp(), b.getSize())
        if b.isStart():
            kind, e = log.control(a)
            sd = b.getStartData()
            assert kind == logs.CONTROL_START and (e.id, e.name, e.type, e.metadata) == (
                sd.entry,
                sd.name,
                sd.type,
                sd.metadata,
            )
        elif b.isFinish():
            assert log.control(a) == (logs.CONTROL_FINISH, b.getFinishEntry())
        elif b.isSetMetadata():
            md = b.getSetMetadataData()
            assert log.control(a) == (logs.CONTROL_SET_METADATA, (md.entry, md.metadata))
        else:
            assert a.payload == bytes(b.getRaw())
    assert count == len(ours) > 400


def test_signals_sorted_typed_and_metadata_updated(tmp_path):
    path = tmp_path / "mixed.wpilog"
    _write_mixed(path)
    sigs, entries, warnings = logs.read_wpilog(
        path, lambda n: n in ("voltage-m-elev", "sysid-test-state-elev", "int")
    )
    assert warnings == []
    v = sigs["voltage-m-elev"]
    assert v.reordered and list(v.times[:2]) == [5e-6, 1000e-6] and v.values[0] == -1.5
    assert v.metadata == "Volts" and entries["voltage-m-elev"].metadata == "Volts"
    assert sigs["sysid-test-state-elev"].values[:1] == ["quasistatic-forward"]
    assert sigs["int"].values[-4] == -243.0  # written in falling time: k = 3 is fourth from the end
    assert "e299" in entries and "darr" in entries


def test_large_log_is_read_in_bounded_memory(tmp_path):
    """400 000 records of a signal nobody wants and 800 of one kept: the reader's peak Python
    memory stays a few MiB (the chunk), far below the file's size."""
    path = tmp_path / "big.wpilog"
    w = wpiutil.DataLogWriter(str(path))
    noise = wlog.DoubleLogEntry(w, "noise", "", 1)
    keep = wlog.DoubleLogEntry(w, "keep", "", 1)
    for k in range(400_000):
        noise.append(float(k), 10 + k)
        if k % 500 == 0:
            keep.append(float(k), 10 + k)
        if k % 10_000 == 0:  # DataLogWriter blocks once its buffers are full until flushed
            w.flush()
    w.flush()
    w.stop()
    del w
    size = path.stat().st_size
    tracemalloc.start()
    sigs, _, _ = logs.read_wpilog(path, lambda n: n == "keep")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert len(sigs["keep"].times) == 800
    print(f"\nlog {size / 1e6:.1f} MB, reader peak {peak / 1e6:.2f} MB")
    assert size > 5e6 and peak < 1.5e6


# --- hostile files ------------------------------------------------------------------------------------


def _head(extra=b""):
    return b"WPILOG" + struct.pack("<HI", 0x0100, len(extra)) + extra


def _rec(entry, ts, payload):
    return bytes([0x20, entry, len(payload)]) + ts.to_bytes(3, "little") + payload


def _start(eid, name, typ="double", meta=""):
    p = bytes([0]) + struct.pack("<I", eid)
    for s in (name, typ, meta):
        p += struct.pack("<I", len(s.encode())) + s.encode()
    return _rec(0, 1, p)


@pytest.mark.parametrize(
    "data, words",
    [
        (b"", "not a WPILog"),
        (b"GARBAGE-NOT-A-LOG", "not a WPILog"),
        (b"WPILOG" + struct.pack("<HI", 0x0200, 0), "version 2.0"),
        (b"WPILOG" + struct.pack("<HI", 0x0100, 1 << 30), "cut off in its header"),
        (_head() + _rec(0, 1, bytes([0]) + struct.pack("<II", 1, 1 << 31)), "past the record's end"),
        (_head() + _rec(0, 1, bytes([7, 1, 0, 0, 0])), "unknown kind 7"),
        (_head() + _start(1, "v") + _rec(1, 2, b"\x00" * 5), "5-byte record"),
        (_head() + _start(1, "v") + _rec(1, 2, struct.pack("<d", math.nan)), "non-finite value (nan)"),
        (_head() + _start(1, "v") + _rec(1, 2, struct.pack("<d", -math.inf)), "non-finite value (-inf)"),
    ],
)
def test_hostile_wpilog_named(tmp_path, data, words):
    path = tmp_path / "bad.wpilog"
    path.write_bytes(data)
    with pytest.raises(InputError) as exc:
        logs.read_wpilog(path, lambda n: True)
    assert str(path) in str(exc.value) and words in str(exc.value)


def test_truncated_log_reads_up_to_the_cut(tmp_path):
    good = _head() + _start(1, "v") + _rec(1, 2, struct.pack("<d", 1.5)) + _rec(1, 3, struct.pack("<d", 2.5))
    for cut, where in ((len(good) - 3, "payload runs past"), (len(good) - 12, "partial record")):
        path = tmp_path / f"cut{cut}.wpilog"
        path.write_bytes(good[:cut])
        sigs, _, warnings = logs.read_wpilog(path, lambda n: True)
        assert list(sigs["v"].values) == [1.5]
        assert len(warnings) == 1 and str(path) in warnings[0] and where in warnings[0]
    # an absurd payload size in the middle of the file reads as a cut-off file
    path = tmp_path / "absurd.wpilog"
    path.write_bytes(
        _head() + _start(1, "v") + bytes([0x2C, 1]) + (1 << 31).to_bytes(4, "little") + b"\x02\x00\x00"
    )
    _, _, warnings = logs.read_wpilog(path, lambda n: True)
    assert "2147483648-byte payload runs past the end" in warnings[0]


def test_missing_file_named(tmp_path):
    with pytest.raises(InputError, match="nothere.wpilog: log: cannot be read"):
        logs.read(tmp_path / "nothere.wpilog", lambda n: True)


# --- CSV -----------------------------------------------------------------------------------------------


def test_csv_columns_and_blanks(tmp_path):
    path = tmp_path / "log.csv"
    path.write_text(
        "Timestamp,/SysId/state,voltage-m-elev,other\n"
        "0.02,quasistatic-forward,1.0,5\n"
        "0.04,,1.5,\n"
        "0.01,none,0.5,7\n"
    )
    sigs, entries, _ = logs.read(path, lambda n: n != "other")
    assert sorted(sigs) == ["/SysId/state", "voltage-m-elev"] and "other" in entries
    v = sigs["voltage-m-elev"]
    assert v.numeric() and list(v.times) == [0.01, 0.02, 0.04] and list(v.values) == [0.5, 1.0, 1.5]
    assert sigs["/SysId/state"].values == ["none", "quasistatic-forward"]


@pytest.mark.parametrize(
    "text, words",
    [
        ("a,b\n1,2\n", "first column must be the time"),
        ("Timestamp,v\nx,2\n", "line 2: the time 'x' is not a number"),
        ("Timestamp,v\ninf,2\n", "not a finite number"),
        ("Timestamp,v\n1,nan\n", "column 'v' holds a non-finite value (nan)"),
    ],
)
def test_hostile_csv_named(tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(InputError) as exc:
        logs.read(path, lambda n: True)
    assert str(path) in str(exc.value) and words in str(exc.value)


# --- the chunked reader against DataLogReader ----------------------------------------------------------


def _robotpys_signals(path):
    """Each entry's (times s, values) as robotpy's DataLogReader reads them, by name, in file order
    then stably sorted by time (the numbers as floats, the strings as text; other types left out)."""
    live, got = {}, {}
    get = {
        "double": lambda r: r.getDouble(),
        "float": lambda r: float(r.getFloat()),
        "int64": lambda r: float(r.getInteger()),
        "boolean": lambda r: float(r.getBoolean()),
        "string": lambda r: r.getString(),
    }
    for r in wlog.DataLogReader(str(path)):
        if r.isStart():
            d = r.getStartData()
            live[d.entry] = (d.name, d.type)
            got.setdefault(d.name, [])
        elif r.isFinish():
            live.pop(r.getFinishEntry(), None)
        elif not r.isControl() and r.getEntry() in live:
            name, typ = live[r.getEntry()]
            if typ in get:
                got[name].append((r.getTimestamp() / 1e6, get[typ](r)))
    return {n: sorted(s, key=lambda x: x[0]) for n, s in got.items()}


def _write_random(path, seed):
    """A log with every record-header width the writer uses: 300 entries (2-byte ids), arrays of 1 to
    600 doubles (1- and 2-byte sizes), raw payloads of 70-200 kB (3-byte sizes, longer than a chunk),
    every standard type, timestamps of 1 to 6 bytes and out of order, an entry finished and its id
    started again under another name."""
    rng = np.random.default_rng(seed)
    w = wpiutil.DataLogWriter(str(path))
    d = [wlog.DoubleLogEntry(w, f"d{k}", "", 1) for k in range(280)]
    s = wlog.StringLogEntry(w, "state", "", 1)
    i = wlog.IntegerLogEntry(w, "int", "", 1)
    f = wlog.FloatLogEntry(w, "float", "", 1)
    b = wlog.BooleanLogEntry(w, "bool", "", 1)
    da = wlog.DoubleArrayLogEntry(w, "darr", "", 1)
    raw = wlog.RawLogEntry(w, "raw", "", 1)
    for k in range(6000):
        t = int(rng.choice([5, 300, 70_000, 2**20, 2**30, 2**40])) + int(rng.integers(0, 200))
        pick = rng.integers(0, 9)
        if pick < 3:
            d[int(rng.integers(0, 280))].append(float(rng.normal()), t)
        elif pick == 3:
            s.append("x" * int(rng.integers(0, 400)) + "é", t)
        elif pick == 4:
            i.append(int(rng.integers(-(2**62), 2**62)), t)
        elif pick == 5:
            f.append(float(rng.normal()), t)
        elif pick == 6:
            b.append(bool(rng.integers(0, 2)), t)
        elif pick == 7:
            da.append(rng.normal(size=int(rng.integers(1, 600))).tolist(), t)
        elif k % 50 == 0:
            raw.append(bytes(int(rng.integers(70_000, 200_000))), t)
        if k == 3000:
            d[7].finish(t)
            d[7] = wlog.DoubleLogEntry(w, "d7-again", "", t)
        if k % 200 == 0:
            w.flush()
    w.flush()
    w.stop()
    del w


@pytest.mark.parametrize("chunk", [300, 1 << 12, logs.CHUNK])
@pytest.mark.parametrize("seed", [0, 1])
def test_signals_equal_robotpys(tmp_path, monkeypatch, chunk, seed):
    """Every entry's samples as read from a chunk of `chunk` bytes at a time equal DataLogReader's:
    the chunk edges fall inside records, headers and long payloads, kept and skipped."""
    path = tmp_path / "random.wpilog"
    _write_random(path, seed)
    monkeypatch.setattr(logs, "CHUNK", chunk)
    want = _robotpys_signals(path)
    for wanted in (lambda n: True, lambda n: n in ("d3", "d7-again", "state", "int", "bool")):
        sigs, entries, warnings = logs.read_wpilog(path, wanted)
        assert warnings == [] and set(entries) == set(want)
        assert set(sigs) == {n for n in want if wanted(n)}
        for name, sig in sigs.items():
            assert list(zip(sig.times, sig.values)) == want[name], name
    assert len(want["state"]) > 500 and len(want["d7-again"]) > 0 and len(want["bool"]) > 500


# --- string signals: codes into their distinct strings ------------------------------------------------


def _raw_start(eid, name: bytes, typ=b"string"):
    p = bytes([0]) + struct.pack("<I", eid)
    for s in (name, typ, b""):
        p += struct.pack("<I", len(s)) + s
    return _rec(0, 1, p)


STATES = [b"none", b"quasistatic-forward", b"quasistatic-reverse", b"dynamic-forward", b"dynamic-reverse"]


def _payloads(seed):
    """A test state's few values in runs, then strings that differ only past their first word, only
    in their last byte, only by a trailing NUL ('a' and 'a\\0'), empty, invalid UTF-8, and longer
    than the reader's word-wise limit (read one by one)."""
    rng = np.random.default_rng(seed)
    out = [STATES[int(k)] for k in np.repeat(rng.integers(0, 5, 300), rng.integers(1, 20, 300))]
    odd = [b"", b"a", b"a\x00", b"\x00", b"\xff", b"\xfe", b"quasi\x80static", b"\xc3", b"\xc3\xa9",
           b"x" * 63 + b"1", b"x" * 63 + b"2", b"x" * 64, b"x" * 65, b"y" * 200, b"12345678", b"123456789"]  # fmt: skip
    for _ in range(3000):
        out.append(
            odd[int(rng.integers(0, len(odd)))] if rng.random() < 0.5 else rng.bytes(int(rng.integers(0, 70)))
        )
    return out


@pytest.mark.parametrize("chunk", [300, 1 << 12, logs.CHUNK])
@pytest.mark.parametrize("collide", [False, True])
def test_string_values_are_each_records_text(tmp_path, monkeypatch, chunk, collide):
    """A string signal's values (codes into its distinct strings) read as each record's bytes decoded
    (a bad byte replaced), whatever the chunk edges, and with every hash made equal (the reader's
    check of each record against its group's first then groups them all exactly)."""
    payloads = _payloads(chunk)
    data = _head() + _raw_start(1, b"state") + _start(2, "v")
    for k, p in enumerate(payloads):
        data += _rec(1, 10 + k, p) + _rec(2, 10 + k, struct.pack("<d", float(k)))
    path = tmp_path / "strings.wpilog"
    path.write_bytes(data)
    monkeypatch.setattr(logs, "CHUNK", chunk)
    if collide:
        monkeypatch.setattr(logs, "_MIX", np.zeros_like(logs._MIX))
    sigs, _, warnings = logs.read_wpilog(path, lambda n: True)
    want = [p.decode("utf-8", "replace") for p in payloads]
    got = sigs["state"].values
    assert warnings == [] and isinstance(got, logs.Texts)
    assert list(got) == want and got == want and got[:3] == want[:3] and got[-1] == want[-1]
    assert sorted(got.table) == sorted(set(want))  # each distinct string once
    assert list(sigs["v"].values) == [float(k) for k in range(len(payloads))]


def test_a_string_signal_costs_a_few_bytes_a_sample(tmp_path):
    """200 000 records of a test state (five values): the signal read holds a code a sample and the
    five strings, not a string a sample (a list of str was ~80 bytes a sample: a 167 MB log of
    SysId records needed 813 MB to fit)."""
    path = tmp_path / "states.wpilog"
    w = wpiutil.DataLogWriter(str(path))
    st = wlog.StringLogEntry(w, "sysid-test-state-lift", "", 1)
    names = [s.decode() for s in STATES]
    for k in range(200_000):
        st.append(names[(k // 1000) % 5], 10 + k)
        if k % 10_000 == 0:
            w.flush()
    w.flush()
    w.stop()
    del w
    tracemalloc.start()
    sigs, _, _ = logs.read_wpilog(path, lambda n: True)
    held, _ = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    sig = sigs["sysid-test-state-lift"]
    assert len(sig.values) == 200_000 and sig.values[999] == "none" and sig.values[1000] == names[1]
    per_sample = held / 200_000
    print(f"\n{per_sample:.1f} bytes a sample held (times 8, code 4)")
    assert per_sample < 20


# --- entry names that are not UTF-8 -------------------------------------------------------------------


def test_names_not_utf8_are_shown_escaped_and_never_alike(tmp_path):
    """Two entries whose names differ in a byte that is not UTF-8 were one name ('v\\ufffd', the
    replacement character) and their samples one signal; each is now its own, its bad bytes shown
    as \\xNN, distinct from a name that holds the text '\\xff' or the replacement character."""
    names = [b"v\xff", b"v\xfe", b"v\\xff", "v\ufffd".encode(), b"v\x1b[2J", b"v"]
    data = _head()
    for eid, name in enumerate(names, start=1):
        data += _raw_start(eid, name, b"double")
    for eid in range(1, len(names) + 1):
        data += _rec(eid, 10 + eid, struct.pack("<d", float(eid)))
    path = tmp_path / "names.wpilog"
    path.write_bytes(data)
    sigs, entries, _ = logs.read_wpilog(path, lambda n: True)
    shown = ["v\\xff", "v\\xfe", "v\\\\xff", "v\ufffd", "v\\x1b[2J", "v"]
    assert list(sigs) == shown == list(entries)
    for eid, name in enumerate(shown, start=1):
        assert list(sigs[name].values) == [float(eid)], name
    assert all(n.isprintable() for n in sigs)


def test_shown_name_is_one_to_one_and_typed_back():
    tricky = ["v", "v\\", "v\\\\", "v\\xff", "v\udcff", "v\x85", "v\\x85", "v\udc85", "v\\u0085", "v\n",
              "v\\n", "v\\x0a", "v\u200b", "v\U000e0001", "é", "v\ufffd"]  # fmt: skip
    shown = [logs.shown_name(n) for n in tricky]
    assert len(set(shown)) == len(tricky), shown
    assert all(s.isprintable() for s in shown)
    assert logs.shown_name("voltage-lift-elevator") == "voltage-lift-elevator"
    assert logs.shown_name(b"m\xff".decode("utf-8", "surrogateescape")) == "m\\xff"
