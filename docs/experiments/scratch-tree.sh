# Sourced by the experiment scripts beside it: a scratch git worktree of pirqa at the commit a
# trial was written against, changed by a patch or a command, built in release.
#
#   source "$(dirname "$0")/scratch-tree.sh"
#   scratch_tree WORKDIR BASE [PATCH | -c COMMAND]
#
# PATCH is a path from the repository's root.
# Sets root (this repository), tree (WORKDIR/tree) and pirqa (its binary), and leaves the shell
# in root. A tree already there is reused as it is (a second run only builds); COMMAND runs
# inside the new tree and must fail where the change did not apply.
scratch_tree() {
    local work=$1 base=$2
    shift 2
    root=$(git rev-parse --show-toplevel)
    mkdir -p "$work"
    cd "$root"
    tree="$work/tree"
    if [ ! -d "$tree" ]; then
        git worktree add --detach "$tree" "$base" || return 1
        case ${1:-} in
            "") ;;
            -c) (cd "$tree" && eval "$2") ;;
            *) git -C "$tree" apply "$root/$1" ;;
        esac || {
            echo "scratch_tree: the change did not apply to $base; remove $tree and look" >&2
            return 1
        }
    fi
    (cd "$tree" && cargo build --release) || return 1
    pirqa="$tree/target/release/pirqa"
}

# The change limit-bound.sh and limit-sparse.sh make for `scratch_tree -c`: limit::MAX_BLOCKS
# raised from 600 to 2000, so the trial build answers walls pirqa itself refuses.
raise_limit_bound="sed -i 's/^pub const MAX_BLOCKS: usize = 600;\$/pub const MAX_BLOCKS: usize = 2000;/' src/limit/mod.rs &&
    grep -q '^pub const MAX_BLOCKS: usize = 2000;\$' src/limit/mod.rs"

# Two scratch trees of plain commits, WORKDIR/before and WORKDIR/after, for the scripts that
# time one build against another. Sets before and after (their binaries) besides what
# scratch_tree sets.
#
#   scratch_builds WORKDIR BEFORE AFTER
scratch_builds() {
    scratch_tree "$1/before" "$2" || return 1
    before=$pirqa
    scratch_tree "$1/after" "$3" || return 1
    after=$pirqa
}
