# Writes a benchmark's figures into tests/bench/RESULTS.md (sourced from the
# repository root): the table row marked <!-- KEY --> gets VALUE in its second
# cell and today's date in its last, so RESULTS.md holds each figure as the
# benchmark last measured it. IGI_RESULTS=off leaves the file alone (a run on
# another machine, or a run with other options than the row's command).
#   results_set KEY VALUE
results_set() {
  [ "${IGI_RESULTS:-on}" = off ] && return 0
  python3 - "$1" "$2" <<'PY'
import datetime, sys
key, value = sys.argv[1], sys.argv[2]
path = "tests/bench/RESULTS.md"
lines = open(path, encoding="utf-8").read().split("\n")
marker = "<!-- %s -->" % key
rows = [i for i, line in enumerate(lines) if marker in line]
if len(rows) != 1:
    sys.exit("results_set: %d rows marked %s in %s" % (len(rows), marker, path))
cells = lines[rows[0]].split("|")
cells[2] = " %s " % value
cells[-2] = " %s " % datetime.date.today().isoformat()
lines[rows[0]] = "|".join(cells)
open(path, "w", encoding="utf-8").write("\n".join(lines))
print("RESULTS.md: %s = %s" % (key, value))
PY
}
