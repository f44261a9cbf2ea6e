# SPDX-License-Identifier: GPL-3.0-or-later
# Helpers for tests/cases/*/run (source this file).
#   setupEnv          source etc/bashrc of this tree
#   makeTmpCase SRC   copy SRC to a fresh temporary directory, cd there
#   check NAME MEASURED EXPECTED RELTOL   print PASS/FAIL line, count failures
#   checkRange NAME MEASURED LO HI        the same for LO <= MEASURED <= HI
#   setKey FILE KEY VALUE   replace "KEY ...;" (first occurrence, any
#                     indentation) in FILE; a missing KEY is a FAIL
#                     (run scripts set top-level entries with demSetEntry)
#   python3: foamField.internal_field(PATH) reads a field's cell values
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd -P)"
# python3 in the tests: "from foamField import internal_field" (lib/foamField.py)
export PYTHONPATH="$top/tests/cases/lib${PYTHONPATH:+:$PYTHONPATH}"
nFail=0

setupEnv() {
    set +u
    . "$top/etc/bashrc" >/dev/null 2>&1 || { echo "FAIL: env: could not source $top/etc/bashrc"; exit 1; }
    command -v demFoam >/dev/null || { echo "FAIL: env: demFoam not built (run ./Allwmake)"; exit 1; }
}

makeTmpCase() {
    tmpRoot=$(mktemp -d "${TMPDIR:-/tmp}/demFoamTest.XXXXXX")
    trap 'rm -rf "$tmpRoot"' EXIT
    cp -r "$1" "$tmpRoot/case"
    cd "$tmpRoot/case" || exit 1
}

# check NAME MEASURED EXPECTED RELTOL  (relative tolerance; EXPECTED 0: absolute)
check() {
    local r
    r=$(python3 -c "
m,e,t=float('$2'),float('$3'),float('$4')
err=abs(m-e)/abs(e) if e!=0 else abs(m)
print('PASS' if err<=t else 'FAIL')")
    echo "$r: $1: $2 vs $3 (tol $4)"
    [ "$r" = PASS ] || nFail=$((nFail+1))
}

# profilingOn: switch OpenFOAM's profiling on in system/controlDict (the
# solvers' timed sections of a step, docs/performance.md)
profilingOn() {
    printf 'profiling\n{\n    active true;\n    cpuInfo false;\n    memInfo false;\n    sysInfo false;\n}\n' >> system/controlDict
}

# checkProfiling NAME FILE SECTION:CALLS ...: each SECTION (its description
# in OpenFOAM's uniform/profiling FILE) was entered CALLS times
checkProfiling() {
    local name=$1 file=$2 sec n; shift 2
    for sec in "$@"; do
        n=$(awk -v d="\"${sec%:*}\";" '$1 == "description" && $2 == d { f = 1 } f && $1 == "calls" { print $2 + 0; exit }' "$file" 2>/dev/null)
        check "$name/profiling: calls of ${sec%:*} in $file" "${n:-nan}" "${sec##*:}" 0
    done
}

# checkRange NAME MEASURED LO HI  (LO <= MEASURED <= HI; -inf/inf for one side)
checkRange() {
    local r
    r=$(python3 -c "print('PASS' if float('$3') <= float('$2') <= float('$4') else 'FAIL')")
    echo "$r: $1: $2 vs [$3, $4]"
    [ "$r" = PASS ] || nFail=$((nFail+1))
}

setKey() {
    sed -i "0,/^\(\s*\)$2\s.*;/s//\1$2 $3;/" "$1"
    # a key that is not there is a broken test, not a silent no-op
    [ "$(sed -n "s/^\s*$2\s\+\([^;]*\);.*/\1/p" "$1" | head -n 1)" = "$3" ] || {
        echo "FAIL: setKey: $1 has no entry '$2 ...;' to set to $3"
        nFail=$((nFail+1)); return 1
    }
}

finish() {
    [ "$nFail" -eq 0 ]
    exit $?
}

# ensureParaView: pvpython (Debian's python3-paraview), xvfb-run and xauth on
# the PATH, installed with apt-get when missing and this is root.  Returns 1
# with the reason in $paraViewMissing when they cannot be had.
ensureParaView() {
    local need="" t0
    paraViewMissing=""
    command -v pvpython >/dev/null || need="$need python3-paraview"
    command -v xvfb-run >/dev/null || need="$need xvfb"
    command -v xauth >/dev/null || need="$need xauth"
    [ -z "$need" ] && return 0
    if [ "$(id -u)" != 0 ]; then
        paraViewMissing="missing Debian packages:$need (not root, cannot apt-get install them)"
        return 1
    fi
    command -v apt-get >/dev/null || {
        paraViewMissing="missing packages:$need and no apt-get on this machine"; return 1; }
    echo "installing:$need (apt-get --no-install-recommends)"
    t0=$(date +%s)
    # shellcheck disable=SC2086
    if ! DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $need; then
        DEBIAN_FRONTEND=noninteractive apt-get update -q \
        && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $need \
        || { paraViewMissing="apt-get install$need failed (no package mirror reachable?)"; return 1; }
    fi
    echo "installed in $(( $(date +%s) - t0 )) s"
    command -v pvpython >/dev/null || {
        paraViewMissing="pvpython still missing after installing python3-paraview"; return 1; }
}
