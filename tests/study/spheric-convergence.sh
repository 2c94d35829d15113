#!/usr/bin/env bash
# How SPHERIC Test 2's impact figures converge with the spacing (Makefile.scenes
# `spheric2-convergence`, docs/validation.md "The peaks against the spacing"). A
# run's first peak is the front's first layer stopped against the face within a
# sample, a push of some rho0 u dx over the sample's time: the single sample's error
# is first order in the spacing. So per sensor the mean peak at each spacing (over
# that spacing's reports, draws at several vector widths where there are several) is
# fitted by least squares with peak = P0 + k dx, and printed: the limit P0 against
# the experiment, and the spacings at which the line is within 30% and within 20% of
# it (the targets of docs/validation.md). The sample-to-sample noise is fitted with
# a power of the spacing, noise = C dx^p, and the spacing where it is 25% printed.
# With three spacings or more the largest distance of a spacing's mean peak from the
# line says whether the first order holds. Beside them the mean rise error at each
# spacing, which no line extrapolates.
#
# Writes PREFIX.csv (one row per sensor) and PREFIX.md (a Markdown table).
#
#   spheric-convergence.sh PREFIX report.csv [...]   (spheric-report.sh's PREFIX.csv;
#                                                     two spacings or more)
set -euo pipefail

die() { echo "spheric-convergence: $*" >&2; exit 2; }
[[ $# -ge 2 ]] || die "usage: spheric-convergence.sh PREFIX report.csv [...] (reports of spheric-report.sh at two spacings or more)"
prefix=$1
shift
for f in "$@"; do [[ -s $f ]] || die "$f: missing or empty (a report of spheric-report.sh)"; done

awk -F, -v OFS=, '
  BEGIN { split("sensor spacing peak_kpa peak_exp_kpa noise rise_error_ms", need, " ") }
  FNR == 1 {
    delete col
    for (c = 1; c <= NF; ++c) col[$c] = c
    for (k = 1; k <= 6; ++k)
      if (!(need[k] in col)) { printf "spheric-convergence: %s: no column %s (not a spheric-report.sh report)\n", FILENAME, need[k] > "/dev/stderr"; bad = 1; exit 2 }
    next
  }
  {
    s = $col["sensor"]; dx = $col["spacing"] + 0
    if (dx <= 0) { printf "spheric-convergence: %s: spacing %s is not a positive length\n", FILENAME, $col["spacing"] > "/dev/stderr"; bad = 1; exit 2 }
    if (!(s in seen)) { seen[s] = 1; order[++sensors] = s }
    if (!((s, dx) in runs)) { spacing[s, ++nspacing[s]] = dx }
    ++runs[s, dx]
    exp_kpa[s] = $col["peak_exp_kpa"] + 0
    v = $col["peak_kpa"]
    if (v != "nan" && v != "-nan") { peak_sum[s, dx] += v; ++peak_n[s, dx] }
    v = $col["rise_error_ms"]
    if (v != "nan" && v != "-nan") { rise_sum[s, dx] += v; ++rise_n[s, dx] }
    v = $col["noise"]
    if (v != "nan" && v != "-nan" && v + 0 > 0) { noise_sum[s, dx] += v; ++noise_n[s, dx] }
  }
  # The interval of spacings (0, largest] where the line P0 + k dx is within the
  # fraction f of the experiment e, as "lo,hi" ("," where there is none).
  function within(p0, k, e, f,    a, b, t) {
    if (k == 0) return (p0 >= e * (1 - f) && p0 <= e * (1 + f)) ? "0,inf" : ","
    a = (e * (1 - f) - p0) / k; b = (e * (1 + f) - p0) / k
    if (a > b) { t = a; a = b; b = t }
    if (a < 0) a = 0
    if (b <= 0) return ","
    return sprintf("%.4g,%.4g", a, b)
  }
  END {
    if (bad) exit 2
    print "sensor,spacings,rises_error_ms,peaks_kpa,peak_exp_kpa,peak_limit_kpa,peak_limit_error,peak_slope_kpa_per_m,peak_fit_residual,within30_min_m,within30_max_m,within20_min_m,within20_max_m,noises,noise_order,noise25_m"
    for (i = 1; i <= sensors; ++i) {
      s = order[i]; m = nspacing[s]
      if (m < 2) { printf "spheric-convergence: sensor %s is at one spacing only (a convergence needs two or more)\n", s > "/dev/stderr"; exit 2 }
      # the spacings from the coarsest down
      for (a = 1; a <= m; ++a) for (b = a + 1; b <= m; ++b)
        if (spacing[s, b] > spacing[s, a]) { t = spacing[s, a]; spacing[s, a] = spacing[s, b]; spacing[s, b] = t }
      n = 0; sx = sy = sxx = sxy = 0; nl = 0; lx = ly = lxx = lxy = 0
      peaks = noises = rises = ""
      for (a = 1; a <= m; ++a) {
        dx = spacing[s, a]
        if (peak_n[s, dx]) {
          y = peak_sum[s, dx] / peak_n[s, dx]; py[a] = y
          ++n; sx += dx; sy += y; sxx += dx * dx; sxy += dx * y
          peaks = peaks (peaks == "" ? "" : ";") sprintf("%g:%.4g:%d", dx, y, peak_n[s, dx])
        } else py[a] = "nan"
        if (rise_n[s, dx]) rises = rises (rises == "" ? "" : ";") sprintf("%g:%.4g", dx, rise_sum[s, dx] / rise_n[s, dx])
        if (noise_n[s, dx]) {
          y = noise_sum[s, dx] / noise_n[s, dx]
          ++nl; lx += log(dx); ly += log(y); lxx += log(dx) ^ 2; lxy += log(dx) * log(y)
          noises = noises (noises == "" ? "" : ";") sprintf("%g:%.4g", dx, y)
        }
      }
      e = exp_kpa[s]
      line = s "," m "," rises "," peaks "," e
      if (n >= 2 && n * sxx - sx * sx > 0) {
        k = (n * sxy - sx * sy) / (n * sxx - sx * sx); p0 = (sy - k * sx) / n
        worst = "nan"
        if (n >= 3) {
          worst = 0
          for (a = 1; a <= m; ++a) if (py[a] != "nan") {
            r = py[a] - (p0 + k * spacing[s, a]); if (r < 0) r = -r
            if (r > worst) worst = r
          }
          worst = (e > 0) ? worst / e : "nan"
        }
        line = line "," sprintf("%.4g,%.4g,%.4g,%.4g", p0, (e > 0) ? p0 / e - 1 : "nan", k, worst)
        line = line "," within(p0, k, e, 0.3) "," within(p0, k, e, 0.2)
      } else line = line ",nan,nan,nan,nan,,,,"
      line = line "," noises
      if (nl >= 2 && nl * lxx - lx * lx > 0) {
        q = (nl * lxy - lx * ly) / (nl * lxx - lx * lx); c = (ly - q * lx) / nl
        line = line "," sprintf("%.3g", q) "," ((q > 0) ? sprintf("%.4g", exp((log(0.25) - c) / q)) : "")
      } else line = line ",nan,"
      print line
    }
  }' "$@" > "$prefix.csv.tmp"
mv "$prefix.csv.tmp" "$prefix.csv"

awk -F, '
  # "0.02 m: 25.8 (5 runs), 0.01 m: 18.4" from "0.02:25.8:5;0.01:18.4:1", each scaled
  function list(cell, scale, unit, digits, sign,    parts, kv, i, out) {
    if (cell == "") return "-"
    split(cell, parts, ";")
    for (i = 1; i in parts; ++i) {
      split(parts[i], kv, ":")
      out = out (i > 1 ? ", " : "") sprintf(sign ? "%s m: %+.*f%s" : "%s m: %.*f%s", kv[1], digits, scale * kv[2], unit)
      if (kv[3] > 1) out = out " (" kv[3] " runs)"
    }
    return out
  }
  function span(lo, hi) {
    if (lo == "") return "none"
    if (hi == "inf") return "any spacing"
    return (lo + 0 > 0) ? sprintf("%.4f to %.4f m", lo, hi) : sprintf("up to %.4f m", hi)
  }
  NR == 1 { next }
  NR == 2 {
    print "| sensor | rise error (ms) | peak (kPa), mean over the runs | limit of peak = P0 + k dx, error | largest distance from the line | within 30% | within 20% | noise | noise order | noise 25% at |"
    print "|---|---|---|---|---|---|---|---|---|---|"
  }
  {
    limit = ($6 == "nan") ? "-" : sprintf("%.2f kPa (experiment %.1f), %+.0f%%", $6, $5, 100 * $7)
    residual = ($9 == "nan") ? "- (two spacings)" : sprintf("%.1f%% of the experiment", 100 * $9)
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, list($3, 1, "", 1, 1), list($4, 1, "", 2), limit, residual, \
      span($10, $11), span($12, $13), list($14, 100, "%", 0), ($15 == "nan") ? "-" : $15, ($16 == "") ? "-" : sprintf("%.4f m", $16)
  }' "$prefix.csv" > "$prefix.md.tmp"
mv "$prefix.md.tmp" "$prefix.md"
cat "$prefix.md"
