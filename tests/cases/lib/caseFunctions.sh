# Helpers for tests/cases/*/run (source this file).
#   setupEnv          source etc/bashrc of this tree
#   makeTmpCase SRC   copy SRC to a fresh temporary directory, cd there
#   check NAME MEASURED EXPECTED RELTOL   print PASS/FAIL line, count failures
#   setKey FILE KEY VALUE   replace "KEY ...;" (first occurrence) in FILE
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../.." && pwd -P)"
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

setKey() {
    sed -i "0,/^\(\s*\)$2\s.*;/s//\1$2 $3;/" "$1"
}

finish() {
    [ "$nFail" -eq 0 ]
    exit $?
}
