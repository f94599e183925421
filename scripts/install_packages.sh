#!/usr/bin/env bash
# Installs the Debian packages named as arguments that this machine lacks (as root, or through sudo);
# setup.sh, fuzz.sh and sanitize_tests.sh call it with the packages each needs.
set -euo pipefail
missing=""
for p in "$@"; do dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"; done
if [ -n "$missing" ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  echo "installing:$missing"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing
fi
