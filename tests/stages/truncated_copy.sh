#!/usr/bin/env bash
# truncated_copy.sh SOURCE DEST — DEST is the first half of SOURCE (a file cut short by a crash).
set -eu
size=$(stat -c %s "$1")
head -c $((size / 2)) "$1" > "$2"
