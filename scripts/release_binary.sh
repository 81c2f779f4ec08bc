#!/usr/bin/env bash
# Sourced by scripts that run studies: sets `bin` to the batstudy binary given as $1, or sets
# up and builds the release binary and uses that.
bin=${1:-}
if [ -z "$bin" ]; then
  bash scripts/setup.sh >/dev/null
  bash scripts/build_release.sh
  bin=target/release/batstudy
fi
