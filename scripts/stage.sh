# Sourced by the test and CI scripts: `stage NAME` starts a named stage and prints how long
# the one before it took; at exit, every stage's time is printed as a table (the per-stage
# figures docs/performance.md reports). Nested scripts append to the same table when
# BATSTUDY_STAGE_LOG names a file.
_stage_name=""
_stage_start=$SECONDS
_stage_log="${BATSTUDY_STAGE_LOG:-}"
if [ -z "$_stage_log" ]; then
  _stage_log=$(mktemp)
  export BATSTUDY_STAGE_LOG=$_stage_log
  _stage_owner=1
else
  _stage_owner=0
fi

_stage_close() {
  if [ -n "$_stage_name" ]; then
    printf '%6d s  %s\n' $((SECONDS - _stage_start)) "$_stage_name" >> "$_stage_log"
  fi
}

# ends the current stage without starting one (before a nested script's own stages)
stage_end() {
  _stage_close
  _stage_name=""
}

stage() {
  _stage_close
  _stage_name="$*"
  _stage_start=$SECONDS
  echo "== $*"
}

_stage_exit() {
  local rc=$?
  _stage_close
  _stage_name=""
  if [ "$_stage_owner" = 1 ]; then
    echo "== Time per stage"
    cat "$_stage_log"
    printf '%6d s  total\n' "$SECONDS"
    rm -f "$_stage_log"
  fi
  return $rc
}
trap _stage_exit EXIT
