#!/usr/bin/env bash
# npm for the replay page's build (web/, cmake/web_bundle.cmake) where none is on PATH. Debian's
# npm package brings 351 packages with it (on a bare Debian 12, more than the rest of `make
# demo`'s set-up: docs/replay.md), while npm itself is one tarball on the npm registry: this fetches
# the pinned npm, checks it against its sha512, unpacks it into .tools/npm ($MJARM_TOOLS/npm) and
# writes .tools/bin/npm, which runs it on the node found on PATH. The build finds it there.
# Idempotent, and quiet when there is nothing to do; a failed fetch leaves nothing behind.
set -euo pipefail
cd "$(dirname "$0")/.."

# npm 10.9 runs on node ^18.17.0 || >=20.5.0: Debian 12's nodejs (18.20) and newer
version=10.9.9
integrity=sha512-1g+6jLQvaIuB4zwvHL7yrXuXcWZwDsCtBX8bbWDqbvJSSr9nPiDDWTHNgwXR27iIcTTW7v3A57hDW9RYv2W4Yg==
url=${MJARM_NPM_URL:-https://registry.npmjs.org/npm/-/npm-$version.tgz}
tools=${MJARM_TOOLS:-.tools}

command -v node >/dev/null || { echo "mjarm setup: npm needs node (Debian: nodejs)" >&2; exit 1; }
[ -f "$tools/npm/.mjarm-npm-$version" ] && [ -x "$tools/bin/npm" ] && exit 0

echo "mjarm setup: fetching npm $version from the npm registry into $tools/npm"
mkdir -p "$tools"
staging=$(mktemp -d "$tools/.npm-XXXXXX")
trap 'rm -rf "$staging"' EXIT
# Python's standard library (Debian's python3, which the set-up installs) fetches, checks and
# unpacks: no curl is needed on a bare machine
python3 - "$url" "$integrity" "$staging" <<'PYTHON'
import base64, hashlib, io, sys, tarfile, urllib.request
url, integrity, staging = sys.argv[1:]
try:
    with urllib.request.urlopen(url, timeout=60) as response:
        data = response.read()
except Exception as error:
    sys.exit(f"mjarm setup: could not fetch {url}: {error}")
algorithm, _, expected = integrity.partition("-")
digest = base64.b64encode(hashlib.new(algorithm, data).digest()).decode()
if digest != expected:
    sys.exit(f"mjarm setup: {url} does not match its pinned {algorithm} "
             f"(got {algorithm}-{digest}): nothing was installed")
with tarfile.open(fileobj=io.BytesIO(data), mode="r:gz") as archive:
    try:
        archive.extractall(staging, filter="data")
    except TypeError:  # a Python before 3.11.4 has no extraction filters; the archive is checked
        archive.extractall(staging)
PYTHON
rm -rf "$tools/npm"
mv "$staging/package" "$tools/npm"
touch "$tools/npm/.mjarm-npm-$version"
mkdir -p "$tools/bin"
cat > "$tools/bin/npm" <<'SH'
#!/bin/sh
# npm from the npm registry (scripts/setup_npm.sh), run on the node found on PATH; pinned, so it
# does not announce newer versions
NPM_CONFIG_UPDATE_NOTIFIER=false exec node "$(dirname "$0")/../npm/bin/npm-cli.js" "$@"
SH
chmod +x "$tools/bin/npm"
