#!/usr/bin/env bash
# The documentation works from a fresh clone (issue 15): every relative link and image in README.md
# and docs/**/*.md resolves to a file tracked by git (anchors to existing headings), and no document
# mentions a path into ../shared or /work. The checker is scripts/check_doc_links.py; it is first run
# on a small planted repository to show it reports what it must (and nothing in code), then on this one.
set -e
source "$(dirname "$0")/lib.sh"
CHECK="$URBANVEC_SOURCE_DIR/scripts/check_doc_links.py"

# 1. A planted repository: one good link of each kind, and one of each fault.
R="$WORK/planted"
mkdir -p "$R/docs/figures" "$R/sample_data"
cat > "$R/README.md" <<'MD'
# Planted

![ok image](docs/figures/map.png) and [ok guide](docs/guide.md#second-part), [ok folder](sample_data)
and [ok anchor](#planted), a [web page](https://example.org/x.md), [a link whose text
runs over two lines](docs/guide.md "with a title").
[missing](docs/nothing.md)
![missing image](docs/figures/none.png)
[bad anchor](docs/guide.md#no-such-heading)
[untracked](docs/untracked.md)
[outside](../shared/specs/spec.md)
[absolute](/etc/passwd)
[ref]: docs/gone.md
<img src="docs/figures/lost.png">
`[in code](docs/code_span.md)` is code, not a link.

```sh
cat [in a fence](docs/fenced.md)
```
MD
cat > "$R/docs/guide.md" <<'MD'
# Guide

## Second part

The spec lives in /work/shared/specs; see also `../shared/CONVENTIONS.md`.
MD
touch "$R/docs/figures/map.png" "$R/sample_data/x.csv" "$R/docs/untracked.md"
git -C "$R" init -q
git -C "$R" add README.md docs/guide.md docs/figures/map.png sample_data/x.csv

set +e
found=$(python3 "$CHECK" "$R" 2>/dev/null)
status=$?
set -e
expect_eq "$status" 1 "checker exit status on the planted repository"
expected="README.md:6: link 'docs/nothing.md': 'docs/nothing.md' does not exist
README.md:7: link 'docs/figures/none.png': 'docs/figures/none.png' does not exist
README.md:8: link 'docs/guide.md#no-such-heading': 'docs/guide.md' has no heading with id '#no-such-heading'
README.md:9: link 'docs/untracked.md': 'docs/untracked.md' exists but is not tracked by git
README.md:10: mentions '../shared/specs/spec.md', a path outside the repository
README.md:10: link '../shared/specs/spec.md' leaves the repository
README.md:11: link '/etc/passwd' is absolute; make it relative to README.md
README.md:12: link 'docs/gone.md': 'docs/gone.md' does not exist
README.md:13: link 'docs/figures/lost.png': 'docs/figures/lost.png' does not exist
docs/guide.md:5: mentions '/work/shared/specs', a path outside the repository
docs/guide.md:5: mentions '../shared/CONVENTIONS.md', a path outside the repository"
expect_eq "$found" "$expected" "checker findings on the planted repository"

# 2. This repository's README.md and docs/.
set +e
found=$(python3 "$CHECK" "$URBANVEC_SOURCE_DIR" 2>&1)
status=$?
set -e
[ "$status" -eq 0 ] || fail "README.md and docs/ have links or paths that a fresh clone cannot follow:
$found"

finish
