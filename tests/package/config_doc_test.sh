#!/usr/bin/env bash
# headingd.toml(5) and the installed headingd.toml cannot drift from the configuration
# reader: every table and key the reader accepts is documented, every documented key is
# accepted, and the man page names each one. The reader is asked itself: headingd
# --check-config on a file with an unknown key answers with the list of keys it accepts.
#
#   config_doc_test.sh HEADINGD PYTHON3 CONFIG_DOC_PY CONFIG_DIR MAN_PAGE CONFFILE
set -euo pipefail
headingd=$1 python=$2 config_doc=$3 config_dir=$4 man_page=$5 conffile=$6
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0

"$python" "$config_doc" --config-dir "$config_dir" --keys | sort > "$work/documented"
echo "documented keys: $(wc -l < "$work/documented")"

# The reader's answer to an unknown key: "... (expected one of: a, b, c; ...)" or
# "(expected a, b, c; ...)" or "(expected [daemon], [log], ...)".
accepted_list() {
  local message
  if message=$("$headingd" --check-config --config "$1" 2>&1); then
    echo "probe $1 was accepted: $message" >&2
    return 1
  fi
  sed -n 's/.*unknown .*(expected \(one of: \)\{0,1\}\([^;)]*\).*/\2/p' <<<"$message" | tr -d '[]' | tr ',' '\n' |
    sed 's/^ *//;s/ *$//' | { grep -v '^$' || true; }
}

printf 'zz_probe_table = 1\n' > "$work/top.toml"
accepted_list "$work/top.toml" | sort > "$work/tables"
cut -d. -f1 "$work/documented" | sort -u > "$work/documented_tables"
if ! diff -u --label "tables the reader accepts" --label "tables documented" "$work/tables" "$work/documented_tables"; then
  fail=1
fi

: > "$work/accepted"
while read -r table; do
  printf '[%s]\nzz_probe_key = 1\n' "$table" > "$work/probe.toml"
  keys=$(accepted_list "$work/probe.toml")
  if [[ -z "$keys" ]]; then
    echo "FAIL: [$table]: the reader did not list its keys: $("$headingd" --check-config --config "$work/probe.toml" 2>&1)"
    fail=1
  fi
  [[ -z "$keys" ]] || sed "s/^/$table./" <<<"$keys" >> "$work/accepted"
  if [[ "$table" == gps ]]; then
    # [gps] has a second key set, read when source = "gpsd" (host, port).
    printf '[gps]\nsource = "gpsd"\nzz_probe_key = 1\n' > "$work/probe.toml"
    accepted_list "$work/probe.toml" | sed "s/^/gps./" >> "$work/accepted"
  fi
done < "$work/tables"
sort -u -o "$work/accepted" "$work/accepted"
echo "keys the reader accepts: $(wc -l < "$work/accepted") in $(wc -l < "$work/tables") tables"
if ! diff -u --label "keys the reader accepts" --label "keys documented in config/*.toml" "$work/accepted" "$work/documented"; then
  fail=1
fi

# Every key in the man page, as "\fBkey\fR" under its table's section.
while IFS=. read -r table key; do
  section=$(awk -v t=".SH [$table]" '$0 == t {on = 1; next} /^\.SH / {on = 0} on' "$man_page")
  if ! grep -qF "\\fB$key\\fR" <<<"$section"; then
    echo "FAIL: $table.$key is not in $man_page under [$table]"
    fail=1
  fi
done < "$work/documented"

# The generated files are those the sources give now.
"$python" "$config_doc" --config-dir "$config_dir" --man "$work/man" --conffile "$work/conffile" \
  --version "$(sed -n 's/^\.TH [^ ]* [0-9] "[^"]*" "headingd \([^"]*\)".*/\1/p' "$man_page")" \
  --date "$(sed -n 's/^\.TH [^ ]* [0-9] "\([^"]*\)".*/\1/p' "$man_page")"
cmp "$work/man" "$man_page" || { echo "FAIL: $man_page is not what config-doc.py makes of $config_dir"; fail=1; }
cmp "$work/conffile" "$conffile" || { echo "FAIL: $conffile is not what config-doc.py makes of $config_dir"; fail=1; }

# The conffile is a good live configuration once its /usr/share/headingd paths are this
# checkout's (tests/package/package_install_test.sh checks the installed one as it is).
sed "s#/usr/share/headingd/#$config_dir/#" "$conffile" > "$work/live.toml"
"$headingd" --check-config --config "$work/live.toml" || fail=1
grep -q '^interface = "can0"' "$conffile" && grep -q '^device = "/dev/gps0"' "$conffile" ||
  { echo "FAIL: the conffile is not the can0 + /dev/gps0 live configuration"; fail=1; }

((fail == 0)) && echo "PASS: $(wc -l < "$work/documented") keys documented, accepted and in the man page"
exit "$fail"
