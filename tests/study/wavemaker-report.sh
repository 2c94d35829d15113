#!/usr/bin/env bash
# A wave flume's regular waves against linear wave theory (Makefile.scenes `wavemaker`,
# examples/wavemaker-piston.toml and wavemaker-flap.toml), from its gauges' surface
# elevation (bw-measure gauge: per gauge the top of the water column over its line).
#
# Theory, for the paddle's period T and stroke S (its whole excursion at the still
# water level) in water of depth h:
#   dispersion  omega^2 = g k tanh(k h) (Newton's iteration), celerity c = omega / k,
#               group velocity c_g = c / 2 (1 + 2 k h / sinh(2 k h))
#   height      Biesel's transfer functions H / S,
#               piston: 2 (cosh(2kh) - 1) / (sinh(2kh) + 2kh)
#               flap hinged at the floor:
#                 4 (sinh(kh) / kh) (kh sinh(kh) - cosh(kh) + 1) / (sinh(2kh) + 2kh)
# Measured, per gauge at distance d from the paddle's face at rest, in the window from
# t_ramp + d / c_g (the end of the ramp has passed the gauge) to (2 L - d) / c_g (the
# first of the waves, reflected by the far wall at distance L from the paddle, is
# back) or the run's end: the zero up-crossings of the elevation about its mean over
# the window (an up-crossing counts after the elevation has been below the mean by a
# tenth of its range: a particle's jitter about the mean makes none), the period T
# between successive up-crossings and the height H, highest less lowest elevation
# between them, each the mean over the whole periods in the window. Per pair of
# gauges a distance dx apart, the celerity dx / lag, the lag the mean over the
# up-crossings of the nearer gauge in its window of the time to the up-crossing of
# the farther one (in its window) nearest to dx / c later: a lag within T / 2 of
# theory's, which fixes the whole periods between the gauges and measures any
# celerity from 2 dx / (2 dx / c + T) up.
#
# Prints a Markdown report and, in a block at its end, one line per gauge and per pair
# for scripts to read:
#   gauge G1 x 1.1 d 1 window 3.56 10 periods 4 T 1.4002 H 0.0912 theory 0.0934 error -2.4%
#   celerity G1-G2 dx 1 lags 4 c 1.812 theory 1.8365 error -1.3%
# with nan and "periods 0" where a window holds no whole period. Exit status 2 on bad
# usage or input.
#
#   wavemaker-report.sh GAUGES.csv --kind piston|flap --period T --stroke S --depth H \
#     --paddle X --wall X [--ramp N] [--end T] --at NAME=x[,y] [--at NAME=x[,y] ...]
#
# --paddle and --wall: x of the paddle's wet face at rest and of the far wall (m);
# --ramp: the ramp's periods (default 2; tests/study/wavemaker-keys.sh); --end: the
# run's end (s; default the last row's time); --at: a gauge of GAUGES.csv and its
# position (bw-measure gauge's --at), in any order.
set -euo pipefail

die() { echo "wavemaker-report: $*" >&2; exit 2; }
usage="usage: wavemaker-report.sh GAUGES.csv --kind piston|flap --period T --stroke S --depth H --paddle X --wall X [--ramp N] [--end T] --at NAME=x[,y] ..."
[[ $# -ge 1 ]] || die "$usage"
gauges=$1
shift
kind='' period='' stroke='' depth='' paddle='' wall='' ramp=2 end='' names='' xs=''
number='^[-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$'
while [[ $# -gt 0 ]]; do
  [[ $# -ge 2 ]] || die "$1: needs a value ($usage)"
  case $1 in
    --kind) kind=$2 ;;
    --period) period=$2 ;;
    --stroke) stroke=$2 ;;
    --depth) depth=$2 ;;
    --paddle) paddle=$2 ;;
    --wall) wall=$2 ;;
    --ramp) ramp=$2 ;;
    --end) end=$2 ;;
    --at)
      [[ $2 =~ ^([A-Za-z_][A-Za-z0-9_]*)=([^,]+)(,.*)?$ ]] || die "--at $2: expected NAME=x or NAME=x,y"
      name=${BASH_REMATCH[1]} x=${BASH_REMATCH[2]}
      [[ $x =~ $number ]] || die "--at $2: x is not a number"
      names+="${names:+ }$name" xs+="${xs:+ }$x" ;;
    *) die "$1: unknown option ($usage)" ;;
  esac
  shift 2
done
[[ $kind == piston || $kind == flap ]] || die "--kind '$kind': expected piston or flap"
for v in period stroke depth paddle wall ramp; do
  [[ -n ${!v} ]] || die "--$v is required ($usage)"
  [[ ${!v} =~ $number ]] || die "--$v ${!v}: expected a number"
done
[[ -z $end || $end =~ $number ]] || die "--end $end: expected a number"
[[ -n $names ]] || die "no gauge: give each as --at NAME=x ($usage)"
[[ -s $gauges ]] || die "$gauges: missing or empty (bw-measure gauge's output)"
IFS=, read -r -a header < "$gauges"
[[ ${header[0]} == time ]] || die "$gauges: expected the columns time,NAME,... of bw-measure gauge"
for n in $names; do
  found=
  for h in "${header[@]:1}"; do [[ $h == "$n" ]] && found=1; done
  [[ -n $found ]] || die "$gauges: has no gauge $n (its columns: ${header[*]:1})"
done

awk -F, -v kind="$kind" -v T="$period" -v S="$stroke" -v h="$depth" -v xp="$paddle" -v xw="$wall" \
    -v nramp="$ramp" -v tend="$end" -v names="$names" -v xs="$xs" -v file="$gauges" '
function sinh(x) { return (exp(x) - exp(-x)) / 2 }
function cosh(x) { return (exp(x) + exp(-x)) / 2 }
function tanh(x) { return sinh(x) / cosh(x) }
function isnum(s) { return s ~ /^[-+]?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ }
function err(m, t) { return 100 * (m - t) / t }
function fmt(x, f) { return x == "nan" ? "nan" : sprintf(f, x) }
function pct(m, t) { return m == "nan" ? "nan" : sprintf("%+.1f%%", err(m, t)) }
# Up-crossings of gauge g in [a, b]: count[g], times up[g, 1..]; H and T per period.
function crossings(g, a, b,   i, m, c, lo, hi, band, armed, n, e, ep, tc) {
  m = 0; c = 0; lo = 1e30; hi = -1e30
  for (i = 1; i <= rows; ++i)
    if (t[i] >= a && t[i] <= b && ((g, i) in v)) { m += v[g, i]; ++c; if (v[g, i] < lo) lo = v[g, i]; if (v[g, i] > hi) hi = v[g, i] }
  count[g] = 0
  if (c < 3) return
  m /= c; band = (hi - lo) / 10; armed = 0; n = 0; ep = ""
  for (i = 1; i <= rows; ++i) {
    if (t[i] < a || t[i] > b || !((g, i) in v)) { ep = ""; continue }
    e = v[g, i] - m
    if (e < -band) armed = 1
    if (armed && e >= 0 && ep != "" && ep < 0) {
      tc = t[i - 1] + (t[i] - t[i - 1]) * (-ep) / (e - ep)
      up[g, ++n] = tc; armed = 0
    }
    ep = e
  }
  count[g] = n
}
BEGIN {
  pi = atan2(0, -1); grav = 9.81
  w = 2 * pi / T
  k = w * w / grav
  for (it = 0; it < 100; ++it) {
    f = grav * k * tanh(k * h) - w * w
    df = grav * tanh(k * h) + grav * k * h * (1 - tanh(k * h) ^ 2)
    dk = f / df; k -= dk
    if (dk < 0 ? -dk < 1e-14 * k : dk < 1e-14 * k) break
  }
  kh = k * h; c = w / k; cg = c / 2 * (1 + 2 * kh / sinh(2 * kh))
  if (kind == "piston") ratio = 2 * (cosh(2 * kh) - 1) / (sinh(2 * kh) + 2 * kh)
  else ratio = 4 * (sinh(kh) / kh) * (kh * sinh(kh) - cosh(kh) + 1) / (sinh(2 * kh) + 2 * kh)
  Hth = ratio * S
  ng = split(names, gname, " "); split(xs, gx, " ")
}
NR == 1 { for (j = 2; j <= NF; ++j) col[$j] = j; next }
{
  ++rows; t[rows] = $1 + 0
  for (g = 1; g <= ng; ++g) { s = $(col[gname[g]]); if (isnum(s)) v[g, rows] = s + 0 }
}
END {
  if (rows < 2) { print "wavemaker-report: " file ": fewer than two rows" > "/dev/stderr"; exit 2 }
  last = tend != "" ? tend + 0 : t[rows]
  L = xw - xp; tr = nramp * T
  printf "# Wave maker: %s, T = %g s, S = %g m, h = %g m\n\n", kind, T, S, h
  printf "Linear theory: k = %.4f 1/m (kh = %.4f, wavelength %.4f m), c = %.4f m/s, c_g = %.4f m/s; " \
    "Biesel H/S = %.4f, H = %.4f m. Paddle face at x = %g m, far wall at x = %g m (L = %g m), ramp %g s, run to %g s.\n\n", \
    k, kh, 2 * pi / k, c, cg, ratio, Hth, xp, xw, L, tr, last
  printf "Each gauge is read from t_ramp + d / c_g (the ramp has passed) to (2 L - d) / c_g (the far wall'"'"'s reflection is back) or the run'"'"'s end, over the whole periods between zero up-crossings in that window.\n\n"
  print "| gauge | x (m) | d (m) | window (s) | periods | T (s) | T error | H (m) | H theory (m) | H error |"
  print "|---|---|---|---|---|---|---|---|---|---|"
  for (g = 1; g <= ng; ++g) {
    d = gx[g] - xp
    a[g] = tr + d / cg; b[g] = (2 * L - d) / cg; if (b[g] > last) b[g] = last
    crossings(g, a[g], b[g])
    n = count[g] - 1; Tm[g] = Hm[g] = "nan"; per[g] = n > 0 ? n : 0
    if (n > 0) {
      st = sh = 0
      for (p = 1; p <= n; ++p) {
        lo = 1e30; hi = -1e30
        for (i = 1; i <= rows; ++i)
          if (t[i] >= up[g, p] && t[i] <= up[g, p + 1] && ((g, i) in v)) { if (v[g, i] < lo) lo = v[g, i]; if (v[g, i] > hi) hi = v[g, i] }
        st += up[g, p + 1] - up[g, p]; sh += hi - lo
      }
      Tm[g] = st / n; Hm[g] = sh / n
    }
    printf "| %s | %g | %g | %.2f - %.2f | %d | %s | %s | %s | %.4f | %s |\n", gname[g], gx[g], d, a[g], b[g], per[g], \
      fmt(Tm[g], "%.4f"), pct(Tm[g], T), fmt(Hm[g], "%.4f"), Hth, pct(Hm[g], Hth)
    line[g] = sprintf("gauge %s x %g d %g window %.2f %.2f periods %d T %s H %s theory %.4f error %s", gname[g], gx[g], d, \
      a[g], b[g], per[g], fmt(Tm[g], "%.4f"), fmt(Hm[g], "%.4f"), Hth, pct(Hm[g], Hth))
  }
  print ""
  print "| gauges | dx (m) | lags | lag (s) | c (m/s) | c theory (m/s) | c error |"
  print "|---|---|---|---|---|---|---|"
  np = 0
  for (g = 1; g <= ng; ++g) for (q = 1; q <= ng; ++q) {
    if (gx[q] <= gx[g]) continue
    dx = gx[q] - gx[g]; lag0 = dx / c; sl = 0; nl = 0
    for (p = 1; p <= count[g]; ++p) {
      best = ""
      for (r = 1; r <= count[q]; ++r) {
        dl = up[q, r] - up[g, p] - lag0; if (dl < 0) dl = -dl
        if (dl < T / 2 && (best == "" || dl < bestd)) { best = up[q, r] - up[g, p]; bestd = dl }
      }
      if (best != "") { sl += best; ++nl }
    }
    cm = nl > 0 ? dx / (sl / nl) : "nan"
    printf "| %s-%s | %g | %d | %s | %s | %.4f | %s |\n", gname[g], gname[q], dx, nl, (nl > 0 ? sprintf("%.4f", sl / nl) : "nan"), \
      fmt(cm, "%.4f"), c, pct(cm, c)
    pline[++np] = sprintf("celerity %s-%s dx %g lags %d c %s theory %.4f error %s", gname[g], gname[q], dx, nl, fmt(cm, "%.4f"), c, pct(cm, c))
  }
  print ""
  print "```"
  for (g = 1; g <= ng; ++g) print line[g]
  for (p = 1; p <= np; ++p) print pline[p]
  print "```"
}' "$gauges"
