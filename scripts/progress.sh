# Progress lines of the reproduction scripts (scripts/reproduce.sh, scripts/precision.sh): sourced,
# not run. The sourcing script sets progress_prefix (e.g. "reproduce") first.

# say TEXT: a line of progress (on a terminal it replaces the "...: running" line before it).
say() {
  if [[ -t 2 ]]; then printf '\r\033[K' >&2; fi
  echo "$progress_prefix: $*" >&2
}
# running TEXT: on a terminal, what runs now, until the next line replaces it.
running() { if [[ -t 2 ]]; then printf '%s: %s: running ...' "$progress_prefix" "$*" >&2; fi; }
# show_log LOG [LINES]: the last lines of a failed command's log, indented, after its path.
show_log() {
  say "  the last lines of $1:"
  tail -n "${2:-12}" "$1" | sed 's/^/    /' >&2
}
# cell_counts LOG...: "MEASURED RESUMED" summed over what each share of a run said when done
# ("shard done: N cells measured, M resumed" or "wrote ... (N cells measured, M resumed; ...)");
# nothing when no log says it.
cell_counts() {
  awk 'match($0, /[0-9]+ cells measured, [0-9]+ resumed/) {
      split(substr($0, RSTART, RLENGTH), w, " "); m += w[1]; r += w[4]; n++ }
    END { if (n) print m, r }' "$@" 2>/dev/null
}
