#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora (tests/fuzz/corpus/<target>/) from the repository's
own files: the gpsd NMEA logs, the DBC files, the demo candump log and CSVs, the configuration
files, the golden calibration, the WMM coefficients and the recording in tests/data. Small
pieces (a few dozen seeds a target, each under 4 kB): libFuzzer mutates from them.
Deterministic: rerunning writes the same files. Seeds named regression-* (inputs that once
crashed a target) are kept; every other seed is rewritten.

Usage: tests/fuzz/make_corpus.py   (from anywhere; writes into the source tree)
"""
import gzip
import pathlib
import random
import struct
import tarfile

repo = pathlib.Path(__file__).resolve().parents[2]
corpus = repo / "tests" / "fuzz" / "corpus"
MAX_SEED = 4000


def write(target, name, data):
    folder = corpus / target
    folder.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8")
    (folder / name).write_bytes(data[:MAX_SEED])


def clear(target):
    folder = corpus / target
    if folder.exists():
        for f in folder.iterdir():
            if not f.name.startswith("regression-"):
                f.unlink()


def slices(data, count, size):
    """`count` pieces of `size` bytes spread evenly over data."""
    if len(data) <= size:
        return [data]
    step = (len(data) - size) // max(count - 1, 1)
    return [data[i * step:i * step + size] for i in range(count)]


def line_groups(text, count, lines_each):
    return ["".join(piece) for piece in slices(text.splitlines(keepends=True), count, lines_each)]


gpsd = sorted((repo / "tests/data/gpsd-logs").glob("*.log"))
demo_nmea = (repo / "config/demo/sim-urban-walk.nmea").read_bytes()
recording = tarfile.open(repo / "tests/data/recordings/sim-walk-30s.tar.gz")


def member(name):
    return recording.extractfile("sim-walk-30s/" + name).read().decode("utf-8", "surrogateescape")


for t in ["nmea_framer", "nmea_sentence", "dbc", "candump_line", "decimal_number", "numeric_csv",
          "daemon_config", "calibration_toml", "wmm_cof", "recording_lines", "pipeline"]:
    clear(t)

# NMEA byte streams (first byte: chunk length) and lines (checksums are recomputed).
for log in gpsd + [repo / "config/demo/sim-urban-walk.nmea"]:
    data = log.read_bytes()
    for i, piece in enumerate(slices(data, 3, 1500)):
        write("nmea_framer", f"{log.stem}-{i}", bytes([i * 21 % 64]) + piece)
    for i, piece in enumerate(slices(data.splitlines(keepends=True), 3, 12)):
        write("nmea_sentence", f"{log.stem}-{i}", b"".join(piece))

# DBC: 8 payload bytes, then the text; whole files and each message on its own.
for dbc in sorted((repo / "config/dbc").glob("*.dbc")):
    text = dbc.read_text()
    write("dbc", dbc.stem, bytes(range(1, 9)) + text.encode())
    blocks = [b for b in text.split("\n\n") if "BO_ " in b]
    for i, block in enumerate(blocks):
        write("dbc", f"{dbc.stem}-message-{i}", bytes([0xA5, 0x5A, 0xFF, 0, 0x80, 1, 2, 3]) + block.encode())
write("dbc", "recording-imu", bytes(8) + member("imu.dbc").encode())

# candump lines: the demo log, the recording's can stream, and the forms the parser knows.
demo_can = gzip.decompress((repo / "config/demo/sim-urban-walk-can.log.gz").read_bytes()).decode()
for i, piece in enumerate(line_groups(demo_can, 12, 20)):
    write("candump_line", f"demo-{i}", piece)
for i, piece in enumerate(line_groups(member("can.000001.log"), 8, 20)):
    write("candump_line", f"recording-{i}", piece)
write("candump_line", "forms",
      "(1700000000.123456) can0 123#DEADBEEF\n"
      "(1700000000.123789) can0 18F02A80#0102030405060708\n"
      "(1700000000.124000) can0 123#R\n(1700000000.124000) can0 123#R4\n"
      "(1700000000.125000) can0 20000004#0000080000000000\n"
      "(1700000000.126000) vcan0 7FF#0011223344556677_C\n"
      "(1700000000.127000) can0 123##1DEAD\n(1700000000.128000) can0 123#DE.AD T\n"
      "# a note\n\n(0.000000) can0 000#\n")

# Decimal numbers: fields of the BROAD trial and the demo truth, then 9-byte doubles.
broad = gzip.decompress((repo / "tests/data/broad/05_undisturbed_slow_rotation_with_breaks_B.csv.gz").read_bytes())
broad_text = broad.decode()
truth = gzip.decompress((repo / "config/demo/sim-urban-walk-truth.csv.gz").read_bytes()).decode()
fields = broad_text.splitlines()[1].split(",")[:12] + truth.splitlines()[1].split(",")[:8]
for i, f in enumerate(fields + ["-0.0", "1e-320", "123456789012345678901234", "nan", "-inf", "0.1000000000000000055511151231257827"]):
    write("decimal_number", f"text-{i}", f)
for i, v in enumerate([0.0, -0.5, 1e8, 0.1, 123456.789, 2.5, 1e300, 5e-324, float("nan"), 1700000000.123456789]):
    write("decimal_number", f"double-{i}", struct.pack("<d", v) + bytes([i]))

# Numeric CSV: kind byte, cut fraction byte, then the header and some rows.
broad_lines = broad_text.splitlines(keepends=True)
truth_lines = truth.splitlines(keepends=True)
for i in range(16):
    lines = broad_lines if i % 2 == 0 else truth_lines
    start = 1 + (i * 7919) % (len(lines) - 30)
    text = lines[0] + "".join(lines[start:start + 8 + i % 5])
    write("numeric_csv", f"{'broad' if i % 2 == 0 else 'truth'}-{i}", bytes([i % 4, 128 + i]) + text.encode())
write("numeric_csv", "blanks-plus-crlf", b"\x00\x00t, gyr_x ,acc_z\r\n+1, 2 ,3\r\n\r\n 4,5,6\n")

# The daemon's configuration: the shipped files, the recording's, and each table alone.
configs = sorted((repo / "config").glob("*.toml"))
for c in configs:
    text = c.read_text()
    write("daemon_config", c.stem, text)
    for i, table in enumerate(text.split("\n[")[1:]):
        write("daemon_config", f"{c.stem}-table-{i}", "[" + table)
for name in ["config.toml", "replay.toml", "config.original.toml"]:
    write("daemon_config", "recording-" + name, member(name))

# Calibration files: the golden one and pieces of it.
calibration = (repo / "tests/golden/broad32_calibrated.calibration.toml").read_text()
write("calibration_toml", "golden", calibration)
for i, table in enumerate(calibration.split("\n[")[1:]):
    write("calibration_toml", f"golden-table-{i}", "[" + table)
write("calibration_toml", "escapes", '[calibration]\nmethod = "a\\u0001\\t\\"b"\nsource_file = \'lit\'\n')

# WMM coefficients: the header and the first degrees, ended by the 9s line.
cof = (repo / "config/wmm/WMM2025.COF").read_text().splitlines(keepends=True)
end = [l for l in cof if l.startswith("9999")]
for degree in range(1, 13):
    terms = [l for l in cof[1:] if l.split() and not l.startswith("9999") and int(l.split()[0]) <= degree]
    write("wmm_cof", f"degree-{degree}", cof[0] + "".join(terms) + "".join(end))
write("wmm_cof", "recording", member("wmm.cof"))

# Recording lines: each stream of the recording, in pieces, and the notes.
for stream in ["can", "gps", "estimator"]:
    for i, piece in enumerate(line_groups(member(stream + ".000001.log"), 8, 10)):
        write("recording_lines", f"{stream}-{i}", piece)
write("recording_lines", "notes", "#flush (1733120000.623456)\n#dropped (1733120000.123456)\n# lost 12 lines\n"
      "123456789012 i\n123456789012 e\n123456789012 c 4711\n123 r \\x00\\\\\\r\\n\n")

# The estimator: random inputs (FuzzedDataProvider's encoding has no file form to seed from).
rng = random.Random(20261202)
for i in range(24):
    size = 64 << (i % 7)
    write("pipeline", f"random-{i}", bytes(rng.randrange(256) for _ in range(min(size, MAX_SEED))))

for folder in sorted(corpus.iterdir()):
    files = list(folder.iterdir())
    print(f"{folder.name}: {len(files)} seeds, {sum(f.stat().st_size for f in files)} bytes")
