# Sourced by the test scripts: `step NAME COMMAND...` runs COMMAND and then prints one line
# "glintlab: step NAME: N s" to stderr (scripts/check.sh collects these lines into its table).
step() {
  local name=$1
  shift
  local start=$SECONDS
  "$@"
  echo "glintlab: step $name: $((SECONDS - start)) s" >&2
}
