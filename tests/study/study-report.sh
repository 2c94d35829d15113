#!/usr/bin/env bash
# The accuracy study's report (Makefile.scenes `study`, docs/validation.md): from the
# CSV of all runs of one scene (header line, then one row per run; study-record's
# columns after `setting,cfl`), mark the efficient frontier, draw error against run
# time, and print the table for docs/validation.md.
#
#   study-report.sh frontier ERRCOL < runs.csv > study.csv
#       appends `frontier_ERRCOL`: 1 for the runs that no other run beats on both
#       wall time and |ERRCOL| (a run that stopped, or whose ERRCOL is nan, is never
#       on it); pipe through it once per error column
#   study-report.sh plot study.csv ERRCOL TITLE YLABEL OUT.png
#       log-log |ERRCOL| against wall time, one curve per setting through its
#       spacings (labelled), and the frontier
#   study-report.sh table study.csv
#       a Markdown table, one row per run, the errors of frontier runs in bold
#   study-report.sh stability stability.csv
#       the stability suite's Markdown table, one row per case
set -euo pipefail

die() { echo "study-report: $*" >&2; exit 2; }

# Column index of a name in the header line.
column() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) { print i; exit } }' "$1"; }

mode=${1:-}
case "$mode" in
  frontier)
    [[ $# -eq 2 ]] || die "usage: study-report.sh frontier ERRCOL < runs.csv"
    awk -F, -v OFS=, -v errname="$2" '
      NR == 1 {
        for (i = 1; i <= NF; ++i) { if ($i == errname) e = i; if ($i == "wall_time") w = i; if ($i == "status") s = i }
        if (!e || !w || !s) { print "study-report: no column " errname ", wall_time or status" > "/dev/stderr"; exit 2 }
        print $0, "frontier_" errname; next
      }
      {
        row[NR] = $0; time[NR] = $w + 0; err[NR] = ($e < 0 ? -$e : $e) + 0
        ok[NR] = ($s == "complete" && $e != "" && tolower($e) !~ /nan/)
      }
      END {
        for (i = 2; i <= NR; ++i) {
          on = ok[i]
          for (j = 2; j <= NR && on; ++j)
            if (j != i && ok[j] && time[j] <= time[i] && err[j] <= err[i] && (time[j] < time[i] || err[j] < err[i])) on = 0
          print row[i], on
        }
      }'
    ;;
  plot)
    [[ $# -eq 6 ]] || die "usage: study-report.sh plot study.csv ERRCOL TITLE YLABEL OUT.png"
    csv=$2 errcol=$3 title=$4 ylabel=$5 png=$6
    setting=$(column "$csv" setting) spacing=$(column "$csv" spacing) wall=$(column "$csv" wall_time)
    error=$(column "$csv" "$errcol") frontier=$(column "$csv" "frontier_$errcol")
    [[ -n $error && -n $frontier ]] || die "$csv: no column $errcol or frontier_$errcol"
    data=$(mktemp)
    trap 'rm -f "$data"' EXIT
    # One gnuplot data block per setting (two blank lines between), coarse to fine.
    settings=$(tail -n +2 "$csv" | cut -d, -f"$setting" | awk '!seen[$0]++')
    for s in $settings; do
      tail -n +2 "$csv" | awk -F, -v s="$s" -v c="$setting" -v sp="$spacing" -v w="$wall" -v e="$error" \
        '$c == s && tolower($e) !~ /nan/ { print $w, ($e < 0 ? -$e : $e), $sp }' | sort -k3,3gr
      printf '\n\n'
    done > "$data"
    # The frontier: its runs by increasing wall time.
    tail -n +2 "$csv" | awk -F, -v w="$wall" -v e="$error" -v f="$frontier" \
      '$f == 1 { print $w, ($e < 0 ? -$e : $e) }' | sort -g >> "$data"
    titles=$(echo $settings)
    count=$(echo "$settings" | wc -w)
    gnuplot <<EOF
set terminal pngcairo size 900,600 font ",11"
set output "$png"
set title "$title"
set logscale xy
set xlabel "wall time (s, 2 cores, PoCL)"
set ylabel "$ylabel"
set grid
set key outside right top
set label 1 "point labels: spacing (m)" at graph 0.01, graph 0.04 font ",9"
plot for [i=0:$((count - 1))] "$data" index i using 1:2 with linespoints pt 7 ps 1.2 title word("$titles", i + 1), \
     for [i=0:$((count - 1))] "$data" index i using 1:2:(sprintf("%g", \$3)) with labels offset 0,0.8 font ",8" notitle, \
     "$data" index $count using 1:2 with lines lw 3 lc rgb "#80000000" dt 2 title "efficient frontier"
EOF
    ;;
  table)
    [[ $# -eq 2 ]] || die "usage: study-report.sh table study.csv"
    awk -F, '
      function bold(text, on) { return on == 1 ? "**" text "**" : text }
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
                dam = ("front_rms" in col)
                floor = ("floor_pressure" in col)
                printf "| setting | spacing (m) | cfl | c0 (m/s) | particles | steps | wall time (s) | %s | worst density error |\n", \
                  dam ? "front RMS vs experiment (a) | after its delay dT | front RMS vs finest (a) | residual RMS (2a)" \
                      : floor ? "pressure (Pa) | pressure error | floor sensor (Pa) | floor sensor error" \
                              : "pressure (Pa) | pressure error"
                printf "|---|---|---|---|---|---|---|%s---|\n", dam ? "---|---|---|---|" : floor ? "---|---|---|---|" : "---|---|"
                next }
      {
        if ($col["status"] != "complete") value = dam ? "stopped | | | " : "stopped | "
        else if (dam) value = sprintf("%s | %.3f (dT %.2f) | %s | %.3f", \
            bold(sprintf("%.3f", $col["front_rms"]), $col["frontier_front_rms"]), $col["front_rms_shifted"], \
            $col["front_shift"], \
            tolower($col["front_vs_finest"]) ~ /nan/ ? "(the finest)" : \
              bold(sprintf("%.3f", $col["front_vs_finest"]), $col["frontier_front_vs_finest"]), $col["residual_rms"])
        else value = sprintf("%.1f | %s", $col["pressure"], \
            bold(sprintf("%+.2f%%", 100 * $col["pressure_error"]), $col["frontier_pressure_error"]))
        if (!dam && floor)
          value = value (($col["status"] != "complete" || tolower($col["floor_pressure"]) ~ /nan/) ? " | | " : \
            sprintf(" | %.1f | %+.2f%%", $col["floor_pressure"], 100 * $col["floor_error"]))
        printf "| %s | %g | %g | %.1f | %d | %d | %.1f | %s | %.2f%% |\n", $col["setting"], $col["spacing"], \
          $col["cfl"], $col["c0"], $col["fluid"], $col["steps"], $col["wall_time"], value, 100 * $col["density_error_worst"]
      }' "$2"
    ;;
  stability)
    [[ $# -eq 2 ]] || die "usage: study-report.sh stability stability.csv"
    awk -F, '
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
                print "| case | expected | verdict | spacing (m) | c0 (m/s) | steps | wall time (s) | worst density error | energy drift | energy rise | particles lost | in solids |"
                print "|---|---|---|---|---|---|---|---|---|---|---|---|"
                next }
      $col["status"] == "refused" {
        printf "| %s | %s | %s | %g | | | | | | | | |\n", $1, $2, $col["verdict"], $col["spacing"]; next }
      {
        printf "| %s | %s | %s%s | %g | %.1f | %d | %.1f | %.2f%% | %+.2f%% | %+.3f%% | %d | %d |\n", $1, $2, \
          $col["verdict"], $col["status"] == "complete" ? "" : " (stopped)", $col["spacing"], $col["c0"], $col["steps"], \
          $col["wall_time"], 100 * $col["density_error_worst"], 100 * $col["energy_drift"], \
          100 * $col["energy_growth"], $col["removed"], $col["inside_solids"]
      }' "$2"
    ;;
  *) die "usage: study-report.sh frontier|plot|table|stability ... (see the comment at the top)" ;;
esac
