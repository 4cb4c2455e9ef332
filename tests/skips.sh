# skips.sh, sourced by the test runners (tests/unit.sh, tests/e2e/run.sh):
# what a run does with checks it skipped. A skip is a check that could
# not run here (no tmux, no python3, a build without assimp, no
# ../shared/models for make test-models): the run has not tested what it
# says it has, so it fails, naming them. ZV_ALLOW_SKIPS=1 lets a local
# run pass with them; under CI (CI set, and not false or 0) nothing
# allows them: tools/deps.sh installs everything the tests need.

# skips_verdict SUITE COUNT: says what COUNT skips mean; status 1 when
# they fail the run
skips_verdict() {
    [ "$2" -eq 0 ] && return 0
    case "${CI:-}" in
    "" | false | 0) ;;
    *)
        echo "$1: $2 skipped, and CI allows none: install what they need (sh tools/deps.sh)"
        return 1
        ;;
    esac
    if [ "${ZV_ALLOW_SKIPS:-0}" = 1 ]; then
        echo "$1: $2 skipped, allowed by ZV_ALLOW_SKIPS=1"
        return 0
    fi
    echo "$1: $2 skipped: install what they need (sh tools/deps.sh), or set ZV_ALLOW_SKIPS=1 to let a local run pass"
    return 1
}
