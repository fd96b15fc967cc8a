#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# drivers/h8300/tails/as on a hand-written listing: the rewritten assembler must be the expected one, and assemble.
# Usage: check_tails.sh <tails/as> <input .s> <expected .s> [options for tails/as]
set -e
tails_as=$1 input=$2 expected=$3
shift 3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp "$input" "$dir/t.s"
sh "$tails_as" "$@" -o "$dir/t.o" "$dir/t.s"
diff "$expected" "$dir/t.s"
[ -s "$dir/t.o" ]
echo "tails: as expected"
