#!/usr/bin/env bash
# `lighthouse` must not link libtorch (cli/net_commands.h): its dependencies, as the dynamic
# loader resolves them, include TBB and nothing named torch.
#   expect_no_libtorch.sh LIGHTHOUSE_EXE
set -u
deps=$(ldd "$1") || { echo "ldd failed on $1"; exit 1; }
grep -q libtbb <<<"$deps" || { echo "ldd lists no libtbb: not the expected binary?"; echo "$deps"; exit 1; }
if grep -i torch <<<"$deps"; then
    echo "$1 links libtorch"
    exit 1
fi
echo "ok: $1 does not link libtorch"
