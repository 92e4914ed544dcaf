#!/bin/bash
# `vtouching completion bash`: commands, each command's options and the values of choice options.
set -eu
source <("$1" completion bash)
complete_words() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _vtouching
  echo "${COMPREPLY[*]}"
}
expect() {
  local want=$1 got
  shift
  got=$(complete_words "$@")
  [ "$got" = "$want" ] || { echo "FAIL: '$*' completes to '$got', not '$want'"; exit 1; }
}
expect "render replay" vtouching re
expect "--pose-sampling" vtouching run --pose-s
expect "--pose-sampling" vtouching --pose-s               # options without a command are run's
expect "paper texture taxel" vtouching render --model ""
expect "sim hid none" vtouching play clip.hjif --glove ""
expect "--trajectory" vtouching client --traj
expect "" vtouching run --traj                             # render's and client's, not run's
expect "client completion convert" vtouching help c
echo PASS
