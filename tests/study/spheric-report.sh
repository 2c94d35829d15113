#!/usr/bin/env bash
# SPHERIC Test 2's report (Makefile.scenes `spheric2`, docs/validation.md "Impact
# pressure"): from the sensors' histories (bw-measure sensor: time,P1,P2,P3,P4 in Pa),
# the experiment's table (examples/data/spheric-test2-pressure.txt) and its measured
# histories (spheric-test2-histories.csv beside the table, or SPHERIC_HISTORIES), per
# sensor
#   rise     the first time the pressure passes 1 kPa (a tenth of the peaks: the
#            water has reached the sensor), against the experiment's first rise
#   peak     the largest pressure and when, against the experiment's
#   mean, sd the mean and standard deviation over 0.45-0.55 s, where the flow runs
#            steadily up the face and a smooth solver reads a steady load; the mean
#            against the experiment's over the same span (nan, with the noise, for a
#            run that stops before 0.55 s: a first impact alone)
#   noise    the RMS of the change from one sample to the next over the same span,
#            over the mean: the acoustic noise (a steady load gives 0); the
#            experiment's the same, from its record averaged over the run's sample
#            interval
#   load     the peak of the pressure's moving mean over SPHERIC_LOAD_WINDOW (0.02 s),
#            the run's and the experiment's record's alike: the load a structure
#            slower than the window feels, where a single sample's peak is the front's
#            first particles striking at once
# Writes PREFIX.csv (one row per sensor), PREFIX.md (a Markdown table) and PREFIX.png
# (the four histories against the experiment's).
#
#   spheric-report.sh sensors.csv spheric-test2-pressure.txt PREFIX SPACING [LABEL=other.csv ...]
# (other runs' sensors drawn in the plot beside the first, e.g. another density scheme;
# SPHERIC_LABEL names the first, "breakwater" by default)
set -euo pipefail

die() { echo "spheric-report: $*" >&2; exit 2; }
[[ $# -ge 4 ]] || die "usage: spheric-report.sh sensors.csv spheric-test2-pressure.txt PREFIX SPACING [LABEL=other.csv ...]"
sensors=$1 reference=$2 prefix=$3 spacing=$4
shift 4
extra=""
for e in "$@"; do
  [[ $e == *=* && -s ${e#*=} ]] || die "$e: expected LABEL=sensors.csv of another run"
  extra+=", \"${e#*=}\" using 1:(column(k+1) / 1000) with lines lw 1 title \"${e%%=*}\""
done
[[ -s $sensors ]] || die "$sensors: missing or empty"
[[ -s $reference ]] || die "$reference: missing or empty"
histories=${SPHERIC_HISTORIES:-$(dirname "$reference")/spheric-test2-histories.csv}
[[ -s $histories ]] || die "$histories: missing or empty (the experiment's histories; set SPHERIC_HISTORIES)"

window=${SPHERIC_LOAD_WINDOW:-0.02}
[[ $window =~ ^[0-9]*\.?[0-9]+$ ]] && awk -v w="$window" 'BEGIN { exit !(w > 0) }' ||
  die "SPHERIC_LOAD_WINDOW: '$window' is not a positive number of seconds"
awk -v OFS=, -v spacing="$spacing" -v window="$window" '
  FILENAME == ARGV[1] {
    if ($0 ~ /^P[0-9]/) { rise[$1] = $2; peak[$1] = $3 * 1000; peak_time[$1] = $4; sub(/^~/, "", peak_time[$1]) }
    next
  }
  FILENAME == ARGV[2] {
    if ($0 ~ /^#/) next
    split($0, v, ",")
    if (v[1] == "time") { for (c = 2; c <= 5; ++c) exp_col[v[c]] = c; next }
    ++rows; exp_t[rows] = v[1]
    for (name in exp_col) exp_p[name, rows] = v[exp_col[name]]
    next
  }
  FNR == 1 {
    n = split($0, head, ",")
    next
  }
  {
    split($0, v, ",")
    t = v[1]
    if (FNR == 2) t_first = t; else if (FNR == 3) interval = t - t_first
    ++samples; run_t[samples] = t
    for (c = 2; c <= n; ++c) {
      p = (v[c] == "nan" || v[c] == "-nan") ? 0 : v[c] + 0
      run_p[c, samples] = p
      if (!(c in first) && p > 1000) first[c] = t
      if (!(c in best) || p > best[c]) { best[c] = p; best_time[c] = t }
      if (t >= 0.45 && t <= 0.55) {
        sum[c] += p; sum2[c] += p * p; count[c]++
        if (c in last) { d = p - last[c]; jump[c] += d * d; jumps[c]++ }
        last[c] = p
      }
    }
  }
  # The experiment over 0.45-0.55 s as the run samples it: its record averaged over
  # intervals of the sample interval of the run (2.5 ms at 400 a second).
  function experiment(name,   k, b, bins, m, d, last_b, have) {
    delete bin_sum; delete bin_n
    for (k = 1; k <= rows; ++k) {
      b = int(exp_t[k] / interval)
      if ((b + 0.5) * interval < 0.45 || (b + 0.5) * interval > 0.55) continue
      bin_sum[b] += exp_p[name, k]; bin_n[b]++
    }
    exp_mean = 0; exp_noise = 0; bins = 0; have = 0
    for (b = int(0.45 / interval) - 1; b <= int(0.55 / interval) + 1; ++b) {
      if (!(b in bin_n)) continue
      m = bin_sum[b] / bin_n[b]
      exp_mean += m; ++bins
      if (have) { d = m - last_b; exp_noise += d * d; ++jumps_e }
      last_b = m; have = 1
    }
    if (!bins) { exp_mean = "nan"; exp_noise = "nan"; return }
    exp_noise = jumps_e ? sqrt(exp_noise / jumps_e) / (exp_mean / bins) : "nan"
    exp_mean /= bins
  }
  # The largest mean of p over the samples within window of each other: the samples
  # in (t_k - window, t_k], k from the first full window on. tt, pp by index 1..m;
  # key: the array key prefix of pp (a column, or a sensor name).
  function load_peak(tt, pp, key, m,   k, lo, sum, best, found) {
    lo = 1; sum = 0; found = 0
    for (k = 1; k <= m; ++k) {
      sum += pp[key, k]
      while (tt[lo] <= tt[k] - window + 1e-9) { sum -= pp[key, lo]; ++lo }
      # a window that reaches back before the first sample is not a full one
      if (k == 1 || tt[k] - tt[1] < window - (tt[k] - tt[k - 1]) - 1e-9) continue
      if (!found || sum / (k - lo + 1) > best) { best = sum / (k - lo + 1); found = 1 }
    }
    return found ? best : "nan"
  }
  END {
    if (interval <= 0) { print "spheric-report: the sensors file has fewer than two samples" > "/dev/stderr"; exit 2 }
    # a run that stops before 0.55 s has no mean over 0.45-0.55 s (a first impact alone)
    covered = run_t[samples] + interval >= 0.55 - 1e-9
    print "sensor,spacing,rise_s,rise_exp_s,rise_error_ms,peak_kpa,peak_time_s,peak_exp_kpa,peak_error,mean_kpa,mean_exp_kpa,mean_error,sd_kpa,noise,noise_exp,load_window_s,load_peak_kpa,load_peak_exp_kpa,load_peak_error"
    for (c = 2; c <= n; ++c) {
      s = head[c]
      m = count[c] ? sum[c] / count[c] : 0
      var = count[c] ? sum2[c] / count[c] - m * m : 0
      sd = var > 0 ? sqrt(var) : 0
      noise = (jumps[c] && m > 0) ? sqrt(jump[c] / jumps[c]) / m : "nan"
      if (!covered) { m = "nan"; sd = "nan"; noise = "nan" }
      r = (c in first) ? first[c] : "nan"
      re = (c in first && s in rise) ? (first[c] - rise[s]) * 1000 : "nan"
      pe = (s in peak && peak[s] > 0) ? best[c] / peak[s] - 1 : "nan"
      jumps_e = 0
      if (s in exp_col) experiment(s); else { exp_mean = "nan"; exp_noise = "nan" }
      me = (m != "nan" && exp_mean != "nan" && exp_mean > 0) ? m / exp_mean - 1 : "nan"
      lp = load_peak(run_t, run_p, c, samples)
      lpe = (s in exp_col) ? load_peak(exp_t, exp_p, s, rows) : "nan"
      le = (lp != "nan" && lpe != "nan" && lpe > 0) ? lp / lpe - 1 : "nan"
      printf "%s,%s,%s,%s,%s,%.3f,%s,%.3f,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", s, spacing, r, rise[s], re, best[c] / 1000, best_time[c], \
        peak[s] / 1000, pe, m == "nan" ? "nan" : sprintf("%.3f", m / 1000), exp_mean == "nan" ? "nan" : sprintf("%.3f", exp_mean / 1000), me, \
        sd == "nan" ? "nan" : sprintf("%.3f", sd / 1000), noise, exp_noise, \
        window, lp == "nan" ? "nan" : sprintf("%.3f", lp / 1000), lpe == "nan" ? "nan" : sprintf("%.3f", lpe / 1000), le
    }
  }' "$reference" "$histories" "$sensors" > "$prefix.csv.tmp"
mv "$prefix.csv.tmp" "$prefix.csv"

awk -F, '
  NR == 1 {
    next
  }
  NR == 2 {
    printf "| sensor | rise (s) | experiment | error (ms) | peak (kPa) | at (s) | experiment | error | mean 0.45-0.55 s (kPa) | experiment | error | sd | noise | experiment | peak of the %g ms mean (kPa) | experiment | error |\n", 1000 * $16
    print "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  }
  # a figure, or "-" where the run has none (a run that stops before 0.55 s has no mean)
  function fig(v, format, scale) { return (v == "nan" || v == "-nan") ? "-" : sprintf(format, scale * v) }
  {
    printf "| %s | %.4f | %.3f | %+.1f | %.2f | %.4f | %.1f | %+.0f%% | %s | %.2f | %s | %s | %s | %.0f%% | %.2f | %.2f | %+.0f%% |\n", $1, $3, $4, $5, $6, \
      $7, $8, 100 * $9, fig($10, "%.2f", 1), $11, fig($12, "%+.0f%%", 100), fig($13, "%.2f", 1), fig($14, "%.0f%%", 100), 100 * $15, \
      $17, $18, 100 * $19
  }' "$prefix.csv" > "$prefix.md.tmp"
mv "$prefix.md.tmp" "$prefix.md"

if command -v gnuplot >/dev/null; then
  gnuplot <<EOF
set terminal pngcairo size 1200,900 font ",10"
set output "$prefix.png.tmp"
set datafile separator ","
set datafile commentschars "#"
set multiplot layout 2,2 title "SPHERIC Test 2 at spacing $spacing m: pressure on the box's face"
do for [k=1:4] {
  set title sprintf("P%d", k)
  set xlabel "t (s)"
  set ylabel "p (kPa)"
  set xrange [0.3:0.7]
  set yrange [-1:*]
  set key top right
  plot "$histories" every ::1 using 1:(column(k+1) / 1000) with lines lw 1.5 lc rgb "black" title "experiment", \
       "$sensors" using 1:(column(k+1) / 1000) with lines lw 1.5 title "${SPHERIC_LABEL:-breakwater}"$extra
}
unset multiplot
EOF
  mv "$prefix.png.tmp" "$prefix.png"
fi
