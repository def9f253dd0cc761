# Sourced by the run_*_benchmarks.sh scripts: the conventions the bench programs share.

# The machine-readable copy of a bench program's report: its "csv," lines, their header lines ("# csv,...")
# kept as comments. usage: extract_csv REPORT.txt > REPORT.csv
extract_csv() {
  grep -E '^(# )?csv,' "$1" | sed 's/^csv,//; s/^# csv,/# /'
}
