#!/usr/bin/python3
"""headingd.toml(5) and the installed /etc/headingd/headingd.toml, both from the commented
configuration files in config/, so that neither can drift from them:

  config/headingd.toml        the daemon's tables ([daemon], [log], ... [nmea_log])
  config/estimator.toml       the keys of [estimator]
  config/can-headingd.toml    the keys of [can] (headingd's own IMU frame set)
  config/gps.toml             the keys of [gps]

A key's documentation is the comment block above it (shared by the keys that follow it
without a comment of their own) and its trailing comment. A commented-out assignment
("# key = value") is an optional key without a default. Every numeric key must state its
range in its documentation ("a .. b" or "One of ..."): the generator fails otherwise.

  config-doc.py --config-dir config --man headingd.toml.5 --conffile headingd.toml
  config-doc.py --config-dir config --keys      # table.key per line (tests)
"""
import argparse
import re
import sys
import tomllib
from dataclasses import dataclass, field

HEADER = re.compile(r"^\[([a-z_]+)\]\s*(#.*)?$")
ASSIGNMENT = re.compile(r"^([a-z][A-Za-z0-9_]*)\s*=")
COMMENTED_ASSIGNMENT = re.compile(r"^#\s?([a-z][A-Za-z0-9_]*) = (\S.*)$")
SUBHEADING = re.compile(r"^--- (.*) ---$")
RANGE = re.compile(r"\.\.|[Oo]ne of")


@dataclass
class Key:
    name: str
    value: object          # parsed TOML value (the default), None for an optional key
    example: str = ""      # an optional key's example value (TOML text)
    trailing: str = ""     # the comment after the value on the same line


@dataclass
class Group:
    doc: list              # comment lines ("" = paragraph break)
    keys: list = field(default_factory=list)


@dataclass
class Table:
    name: str
    intro: list = field(default_factory=list)
    groups: list = field(default_factory=list)


@dataclass
class ConfigFile:
    preamble: list = field(default_factory=list)
    tables: list = field(default_factory=list)
    epilogue: list = field(default_factory=list)


def split_comment(line):
    """(code, comment) of a TOML line: the first '#' outside a string starts the comment."""
    quote = None
    for i, c in enumerate(line):
        if quote:
            if c == "\\" and quote == '"':
                continue
            if c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == "#":
            return line[:i].rstrip(), line[i + 1:].strip()
    return line.rstrip(), ""


def parse_file(path):
    parsed = ConfigFile()
    pending = []
    table = None
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for number, raw in enumerate(lines, 1):
        line = raw.strip()
        if not line:
            if pending and pending[-1] != "":
                pending.append("")
            continue
        commented = COMMENTED_ASSIGNMENT.match(line)
        if commented and table is not None:
            key = Key(commented.group(1), None, example=split_comment(commented.group(2))[0])
            attach(table, pending, key)
            pending = []
            continue
        if line.startswith("#"):
            pending.append(line[1:].strip())
            continue
        header = HEADER.match(line)
        if header:
            flush(parsed, table, pending)
            pending = []
            table = Table(header.group(1))
            parsed.tables.append(table)
            continue
        if not ASSIGNMENT.match(line) or table is None:
            sys.exit(f"{path}:{number}: expected a [table], a key = value or a comment")
        code, comment = split_comment(line)
        try:
            (name, value), = tomllib.loads(code).items()
        except (tomllib.TOMLDecodeError, ValueError) as e:
            sys.exit(f"{path}:{number}: {e}")
        attach(table, pending, Key(name, value, trailing=comment))
        pending = []
    parsed.epilogue = strip_breaks(pending)
    return parsed


def strip_breaks(doc):
    while doc and doc[0] == "":
        doc = doc[1:]
    while doc and doc[-1] == "":
        doc = doc[:-1]
    return doc


def attach(table, pending, key):
    doc = strip_breaks(pending)
    if doc or not table.groups:
        table.groups.append(Group(doc))
    table.groups[-1].keys.append(key)


def flush(parsed, table, pending):
    doc = strip_breaks(pending)
    if table is None:
        parsed.preamble = doc
    elif doc:
        table.intro += ([""] if table.intro else []) + doc


def load(config_dir):
    """The daemon's configuration: headingd.toml with [estimator], [can] and [gps] filled in
    from their own files. Returns (main file, tables in order)."""
    main = parse_file(f"{config_dir}/headingd.toml")
    parts = {"estimator": parse_file(f"{config_dir}/estimator.toml"),
             "can": parse_file(f"{config_dir}/can-headingd.toml"),
             "gps": parse_file(f"{config_dir}/gps.toml")}
    tables = []
    for table in main.tables:
        if table.name in parts and table.groups:
            sys.exit(f"{config_dir}/headingd.toml: [{table.name}] is documented in its own file; keep its keys there")
        tables.append(table)
    estimator = next(t for t in tables if t.name == "estimator")
    for name, part in parts.items():
        (own,) = [t for t in part.tables if t.name == name]
        if name == "estimator":
            own.intro = estimator.intro + [""] + part.preamble
            tables[tables.index(estimator)] = own
        else:
            own.intro = part.preamble + ([""] + own.intro if own.intro else [])
            tables.append(own)
    for table in tables:
        for group in table.groups:
            text = " ".join(group.doc + [k.trailing for k in group.keys])
            for key in group.keys:
                if isinstance(key.value, (int, float)) and not isinstance(key.value, bool) and not RANGE.search(text):
                    sys.exit(f"{config_dir}: [{table.name}] {key.name}: its comment states no range (\"a .. b\")")
    return main, tables


def toml_value(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return repr(value) if isinstance(value, float) else str(value)


# --- headingd.toml(5) ---

def roff(text):
    text = text.replace("\\", "\\e").replace("-", "\\-")
    return "\\&" + text if text[:1] in (".", "'") else text


def roff_paragraphs(doc):
    out = []
    for line in doc:
        sub = SUBHEADING.match(line)
        if line == "":
            out.append(".sp")
        elif sub:
            out += [".sp", ".I " + roff(sub.group(1))]
        else:
            out.append(roff(line))
    return out


def man_page(main, tables, version, date):
    out = [f'.TH HEADINGD.TOML 5 "{date}" "headingd {version}" "File Formats"',
           ".\\\" Generated by packaging/config-doc.py from config/*.toml: do not edit.",
           ".SH NAME", "headingd.toml \\- configuration of headingd, the heading and attitude daemon",
           ".SH SYNOPSIS", ".B /etc/headingd/headingd.toml",
           ".SH DESCRIPTION"]
    out += roff_paragraphs(main.preamble)
    out += [".PP", "Each key is shown with its default value. The [can] table shows the values for",
            "headingd's own IMU frame set (config/can\\-headingd.toml); its keys",
            "without a default (dbc, gyro, accel) must be given. A key shown as",
            "\\fIkey\\fR (optional) has no default; the example value is one that could be set.",
            "The installed /etc/headingd/headingd.toml is a live configuration: SocketCAN",
            "can0 with /usr/share/headingd/dbc/headingd_imu.dbc, the GPS on /dev/gps0, the",
            "World Magnetic Model from /usr/share/headingd/wmm; every other key is shown there",
            "commented out with its default."]
    for table in tables:
        out += [".SH " + roff(f"[{table.name}]")]
        if table.name == "can" and main.epilogue:
            out += roff_paragraphs(main.epilogue) + [".PP"]
        out += roff_paragraphs(table.intro)
        for group in table.groups:
            for i, key in enumerate(group.keys):
                out.append(".TP" if i == 0 else ".TQ")
                # A text line, not a macro: the values hold double quotes.
                if key.value is None:
                    out.append(f"\\fB{roff(key.name)}\\fR (optional), e.g. {roff(key.example)}")
                else:
                    out.append(f"\\fB{roff(key.name)}\\fR = {roff(toml_value(key.value))}")
            out += roff_paragraphs(group.doc) or [""]
            trailing = [k.trailing for k in group.keys if k.trailing]
            if trailing:
                out += [".br"] + [roff(f"{k.name}: {k.trailing}") + "\n.br" for k in group.keys if k.trailing]
    out += [".SH FILES", ".TP", "/etc/headingd/headingd.toml", "the configuration the unit reads",
            ".TP", "/usr/share/headingd/", "WMM coefficients (wmm/), DBC files (dbc/), the demo capture (demo/)",
            ".TP", "/usr/share/doc/headingd/examples/", "headingd.toml, demo.toml, can\\-openimu.toml, a systemd\\-networkd",
            "file for can0 and a udev rule for /dev/gps0",
            ".SH SEE ALSO", "\\fBheadingd\\fR(8), \\fBheadingd\\-replay\\fR(1), \\fBheadingd\\-calibrate\\fR(1),",
            "\\fBsystemd.network\\fR(5), \\fBudev\\fR(7)"]
    return "\n".join(out) + "\n"


# --- the installed configuration ---

# The live configuration's own values; every other key is written commented out.
LIVE = {
    ("daemon", "wmm"): "/usr/share/headingd/wmm/WMM2025.COF",
    ("can", "interface"): "can0",
    ("can", "dbc"): "/usr/share/headingd/dbc/headingd_imu.dbc",
    ("can", "gyro"): None, ("can", "accel"): None, ("can", "mag"): None, ("can", "sequence"): None,
    ("gps", "enabled"): True,
    ("gps", "device"): "/dev/gps0",
}


def comment_lines(doc):
    return ["#" if line == "" else "# " + line for line in doc]


def conffile(main, tables):
    out = ["# /etc/headingd/headingd.toml: headingd's live configuration, as installed by the",
           "# Debian package: the IMU on SocketCAN can0 (headingd's own frame set, decoded by",
           "# /usr/share/headingd/dbc/headingd_imu.dbc), the GPS receiver on /dev/gps0 (a udev",
           "# symlink: /usr/share/doc/headingd/examples/), the World Magnetic Model from",
           "# /usr/share/headingd/wmm/. Keys written commented out keep the default shown.",
           "# Check an edited file with: headingd --check-config --config /etc/headingd/headingd.toml",
           "# then: systemctl restart headingd. headingd.toml(5) documents every key.",
           "# (Generated by packaging/config-doc.py from config/*.toml.)", "#"]
    out += comment_lines(main.preamble)
    for table in tables:
        out += ["", f"[{table.name}]"]
        if table.name == "can" and main.epilogue:
            out += comment_lines(main.epilogue) + ["#"]
        out += comment_lines(table.intro)
        for group in table.groups:
            out += comment_lines(group.doc)
            for key in group.keys:
                trailing = f"  # {key.trailing}" if key.trailing else ""
                if (table.name, key.name) in LIVE:
                    value = LIVE[(table.name, key.name)]
                    value = key.value if value is None else value
                    out.append(f"{key.name} = {toml_value(value)}{trailing}")
                elif key.value is None:
                    out.append(f"# {key.name} = {key.example}")
                else:
                    out.append(f"# {key.name} = {toml_value(key.value)}{trailing}")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--config-dir", required=True, help="the repository's config/ folder")
    parser.add_argument("--man", help="write headingd.toml(5) (roff) here")
    parser.add_argument("--conffile", help="write the installed /etc/headingd/headingd.toml here")
    parser.add_argument("--keys", action="store_true", help="print table.key of every documented key")
    parser.add_argument("--version", default="")
    parser.add_argument("--date", default="", help="the man page's date (e.g. from SOURCE_DATE_EPOCH)")
    args = parser.parse_args()
    main_file, tables = load(args.config_dir)
    if args.man:
        with open(args.man, "w", encoding="utf-8") as f:
            f.write(man_page(main_file, tables, args.version, args.date))
    if args.conffile:
        with open(args.conffile, "w", encoding="utf-8") as f:
            f.write(conffile(main_file, tables))
    if args.keys:
        for table in tables:
            for group in table.groups:
                for key in group.keys:
                    print(f"{table.name}.{key.name}")


if __name__ == "__main__":
    main()
