# Sourced first by every shell script in scripts/: with -h or --help as its first argument, the
# script prints its header comment (what it is for and how it is called) and exits 0.
case "${1:-}" in
  -h | --help)
    awk 'NR == 1 { next } !/^#/ { exit } { sub(/^# ?/, ""); print }' "$0"
    exit 0
    ;;
esac
