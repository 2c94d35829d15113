#!/usr/bin/env bash
# The spread of SPHERIC Test 2's figures over runs that differ only in their last
# bits (Makefile.scenes `spheric2-spread`, docs/validation.md "Impact pressure"): the
# same scene with the kernels built at several vector widths, whose sums add in other
# orders, as another CPU's SIMD width or a GPU's would, or draws of the scene's own
# (fluid.seed: its particles a thousandth of a spacing off the lattice, docs/scene.md
# "Draws"). An impact is chaotic at the
# particle scale, so a peak or a sample-to-sample noise that one run prints is one
# draw; the spread says how far another machine's run may read from it, and a target
# is met only when the whole range meets it. One report gives that run's figures
# (its range is itself), so one width's draw prints the same table.
#
# From each run's report (spheric-report.sh's PREFIX.csv, one row per sensor), per
# sensor and figure (rise error, peak error, mean error over 0.45-0.55 s, noise, the
# error of the peak of the moving mean) the mean over the runs, their least and
# largest value and their standard deviation (n - 1; an ensemble of draws by
# fluid.seed reads its spread from it). Writes PREFIX.csv (one row per sensor) and
# PREFIX.md (a Markdown table, "mean ± sd (least to largest)").
#
#   spheric-spread.sh PREFIX report.csv [report.csv ...]
set -euo pipefail

die() { echo "spheric-spread: $*" >&2; exit 2; }
[[ $# -ge 2 ]] || die "usage: spheric-spread.sh PREFIX report.csv [report.csv ...] (one report or more)"
prefix=$1
shift
for f in "$@"; do [[ -s $f ]] || die "$f: missing or empty (a report of spheric-report.sh)"; done

awk -F, -v OFS=, '
  FNR == 1 {
    delete col
    for (c = 1; c <= NF; ++c) col[$c] = c
    for (k = 1; k <= 6; ++k)
      if (!(figure[k] in col) || !("sensor" in col)) { printf "spheric-spread: %s: no column %s (not a spheric-report.sh report)\n", FILENAME, figure[k] > "/dev/stderr"; bad = 1; exit 2 }
    ++runs
    next
  }
  BEGIN { split("rise_error_ms peak_error mean_error noise load_peak_error noise_exp", figure, " ") }
  {
    s = $col["sensor"]
    if (!(s in seen)) { seen[s] = 1; order[++sensors] = s }
    if (("load_window_s" in col) && window == "") window = $col["load_window_s"]
    ++count[s]
    for (k = 1; k <= 6; ++k) {
      v = $col[figure[k]]
      if (v == "nan" || v == "-nan") continue
      v += 0
      sum[s, k] += v; sq[s, k] += v * v; n[s, k]++
      if (!((s, k) in lo) || v < lo[s, k]) lo[s, k] = v
      if (!((s, k) in hi) || v > hi[s, k]) hi[s, k] = v
    }
  }
  END {
    if (bad) exit 2
    header = "sensor,runs"
    for (k = 1; k <= 5; ++k) header = header "," figure[k] "_mean," figure[k] "_min," figure[k] "_max"
    sds = ""
    for (k = 1; k <= 5; ++k) sds = sds "," figure[k] "_sd"
    print header ",noise_exp,load_window_s" sds
    for (i = 1; i <= sensors; ++i) {
      s = order[i]
      if (count[s] != runs) { printf "spheric-spread: sensor %s is in %d of the %d reports\n", s, count[s], runs > "/dev/stderr"; exit 2 }
      line = s "," runs
      for (k = 1; k <= 5; ++k)
        line = line "," (n[s, k] ? sprintf("%.4g,%.4g,%.4g", sum[s, k] / n[s, k], lo[s, k], hi[s, k]) : "nan,nan,nan")
      # The standard deviation over the runs (n - 1): with the mean, what an ensemble says.
      sds = ""
      for (k = 1; k <= 5; ++k) {
        m = n[s, k]
        v = m >= 2 ? (sq[s, k] - sum[s, k] * sum[s, k] / m) / (m - 1) : -1
        sds = sds "," (m >= 2 ? sprintf("%.4g", sqrt(v > 0 ? v : 0)) : "nan")
      }
      print line "," (n[s, 6] ? sprintf("%.4g", sum[s, 6] / n[s, 6]) : "nan") "," window sds
    }
  }' "$@" > "$prefix.csv.tmp"
mv "$prefix.csv.tmp" "$prefix.csv"

awk -F, '
  # "mean +- sd (least to largest)", each scaled and with its digits; one run has no sd
  function cell(m, a, b, sd, scale, unit, digits) {
    if (m == "nan") return "-"
    return sprintf("%+.*f%s%s (%+.*f to %+.*f)", digits, scale * m, unit, \
                   sd == "nan" ? "" : sprintf(" ± %.*f", digits, scale * sd), digits, scale * a, digits, scale * b)
  }
  NR == 1 { next }
  NR == 2 {
    printf "| sensor | runs | rise error (ms) | peak error | mean error 0.45-0.55 s | noise | experiment | peak of the %g ms mean, error |\n", 1000 * $19
    print "|---|---|---|---|---|---|---|---|"
  }
  {
    noise = ($12 == "nan") ? "-" : sprintf("%.0f%%%s (%.0f to %.0f%%)", 100 * $12, \
                                         $23 == "nan" ? "" : sprintf(" ± %.0f", 100 * $23), 100 * $13, 100 * $14)
    printf "| %s | %d | %s | %s | %s | %s | %s | %s |\n", $1, $2, cell($3, $4, $5, $20, 1, "", 1), \
      cell($6, $7, $8, $21, 100, "%", 0), cell($9, $10, $11, $22, 100, "%", 0), noise, \
      ($18 == "nan") ? "-" : sprintf("%.0f%%", 100 * $18), cell($15, $16, $17, $24, 100, "%", 0)
  }' "$prefix.csv" > "$prefix.md.tmp"
mv "$prefix.md.tmp" "$prefix.md"
cat "$prefix.md"
