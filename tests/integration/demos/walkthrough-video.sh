#!/bin/sh
# SPDX-License-Identifier: MIT
# The walkthrough's video: a tiny run with an image of every frame (5 frames
# of 64 x 64, --png-every 1), then tools/video-walkthrough.sh on its folder.
# ffprobe must count one video frame per route frame, of the size the layout
# gives: frame | top view per strategy, two columns past two strategies.
# Without every frame's images the script says so and fails.
# Usage: walkthrough-video.sh WALKTHROUGH VIDEO-WALKTHROUGH
set -u
walkthrough=$1
video=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}
command -v ffprobe >/dev/null || { echo "FAIL: ffmpeg is not installed (Debian: apt-get install ffmpeg)"; exit 1; }

if ! "$walkthrough" --route dense --frames 5 --size 64 --png-every 1 --strategies vfc,ideal,om-ps \
        --out "$dir/run" >"$dir/run.log" 2>&1; then
    cat "$dir/run.log"
    fail "the walkthrough failed"
fi

# check STRATEGIES WIDTH HEIGHT: the video of these strategies has 5 frames of WIDTH x HEIGHT.
check() {
    strategies=$1
    # shellcheck disable=SC2086  # the strategies are separate arguments
    printed=$("$video" "$dir/run" $strategies 2>"$dir/video.err") || { cat "$dir/video.err"; fail "$video $strategies failed"; return; }
    [ "$printed" = "$dir/run/route.mp4" ] || fail "$video printed '$printed'"
    got=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height \
              -of csv=p=0 "$dir/run/route.mp4")
    if [ "$got" = "$2,$3,5" ]; then
        echo "ok: ${strategies:-every strategy}: $got (width,height,frames)"
    else
        fail "${strategies:-every strategy}: ffprobe says '$got', expected '$2,$3,5'"
    fi
}
check "" 256 128          # three strategies: two columns of 128 x 64 tiles, two rows
check "om-ps" 128 64
check "vfc om-ps" 128 128

# An image missing: a message naming it, a failing status.
rm "$dir/run/vfc-0003.png"
if "$video" "$dir/run" vfc >/dev/null 2>"$dir/missing.err" || ! grep -q 'png-every 1' "$dir/missing.err"; then
    fail "a missing frame: $(cat "$dir/missing.err")"
fi

[ $failures -eq 0 ] || { echo "$failures failed"; exit 1; }
echo "the walkthrough's video has a frame per route frame, frame and top view side by side"
