#!/usr/bin/env bash
# The browser of tests/python/test_verify_page.py: Debian's chromium, run headless to
# open the results page of `cosim verify TREE --html`, check that every image loads and
# keep a screenshot. Installs it with apt-get when it is missing and this runs as root
# (CI); otherwise asks for it and fails, so that the page test never runs without it.
set -euo pipefail
if command -v chromium >/dev/null 2>&1; then
    exit 0
fi
if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium >/dev/null
    command -v chromium >/dev/null 2>&1 && exit 0
    echo "apt-get installed chromium but the command chromium is not on PATH" >&2
    exit 1
fi
echo "chromium is missing (the results page test needs it): install it (Debian: apt-get install chromium)" >&2
exit 1
