#!/usr/bin/env bash
# Install a Debian package a command needs, as `./springlab setup` does: on a terminal it
# asks (sudo when not root); as root without a terminal (CI) it installs and says so;
# without apt-get, or when the answer is no, it prints how to get it and fails.
#
# usage: tools/offer_package.sh COMMAND PACKAGE ELSEWHERE
#   COMMAND    the springlab command that needs it (for the messages)
#   PACKAGE    the Debian package
#   ELSEWHERE  how to get it without apt-get
set -euo pipefail
command="$1" package="$2" elsewhere="$3"
say() { printf 'springlab %s: %s\n' "$command" "$*" >&2; }
if ! command -v apt-get >/dev/null; then
  say "$package is missing: $elsewhere"
  exit 2
fi
sudo=()
if [[ "$(id -u)" == 0 && ! -t 0 ]]; then
  say "installing $package (apt-get, as root without a terminal, as in CI)"
elif [[ -t 0 ]]; then
  answer=""
  read -r -p "springlab $command: $package is missing; install it with apt-get? [y/N] " answer
  [[ "$answer" =~ ^[yY] ]] || { say "not installed; to do it yourself: sudo apt-get install $package"; exit 2; }
  [[ "$(id -u)" == 0 ]] || sudo=(sudo)
else
  say "$package is missing and there is no terminal to ask: sudo apt-get install $package"
  exit 2
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "$package" >/dev/null
say "$package installed"
