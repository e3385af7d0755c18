#!/usr/bin/env bash
# The shared libraries that the importers of tests/python/test_importers_*.py need beyond
# their PyPI wheels: ecospy's libecosc.so links Debian's libtbb12 (oneTBB). Installs it
# with apt-get when it is missing and this runs as root (CI); otherwise asks for it and
# fails, so that the importer tests never run (or skip) without it.
set -euo pipefail
# Whether the loader's cache lists libtbb.so.12. Not `ldconfig -p | grep -q`: grep -q
# exits at the first match, ldconfig then dies of SIGPIPE and pipefail makes the test
# fail although the library is there (it did in CI, at random).
has_tbb() {
    local cache
    cache="$(ldconfig -p)"
    [[ "$cache" == *"libtbb.so.12 "* ]]
}
if has_tbb; then
    exit 0
fi
if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libtbb12 >/dev/null
    has_tbb && exit 0
    echo "apt-get installed libtbb12 but libtbb.so.12 is not in the loader's cache" >&2
    exit 1
fi
echo "libtbb.so.12 is missing (ecospy needs it): install it (Debian: apt-get install libtbb12)" >&2
exit 1
