# Shared helpers of the bench scripts (sourced, not run): the walkthrough's
# results are read from its summary.csv by column name.
source "$(dirname "${BASH_SOURCE[0]}")/../tools/lib.sh"

# field SUMMARY STRATEGY COLUMN: one value of the walkthrough's summary.csv.
field() {
    awk -F, -v strategy="$2" -v column="$3" '
        NR == 1 { for (i = 1; i <= NF; i++) at[$i] = i
                  if (!(column in at)) { print "no column " column > "/dev/stderr"; exit 1 } next }
        $1 == strategy { print $at[column]; found = 1 }
        END { if (!found) print "-" }' "$1"
}

# The minimum-occluder-set database for the given occu-preprocess build
# options, made once into build/occluders/ (its path on stdout).
occluder_db() {
    "$OCCU_ROOT/build/demos/occu-preprocess" build --cache "$OCCU_ROOT/build/occluders" "$@"
}

# The occluder-skin database of the default city at voxel size $1 (default
# 0.25 m: skins within 0.19 m of their meshes' faces, about 8 s to make),
# made once into build/occluders/ and again when occu-preprocess changes
# (its path on stdout).
skins_db() {
    local voxel=${1:-0.25} dir=$OCCU_ROOT/build/occluders
    local file=$dir/skins-voxel-$voxel.txt
    if [ ! -f "$file" ] || [ "$OCCU_ROOT/build/demos/occu-preprocess" -nt "$file" ]; then
        mkdir -p "$dir"
        "$OCCU_ROOT/build/demos/occu-preprocess" skins --out "$file.tmp" --voxel-size "$voxel" >&2
        mv "$file.tmp" "$file"
    fi
    echo "$file"
}

# Walkthrough arguments that give the skin strategies (skins, hzb, hom,
# shadow, planes) the skin database, when the comma-separated strategy list
# $1 has one.
skin_args() {
    if [[ ,$1 =~ ,(skins|hzb|hom|shadow|planes)[,:-]|,(skins|hzb|hom|shadow|planes)$ ]] &&
       [[ $1 != *skin-database* ]]; then
        echo "--set skin-database=$(skins_db)"
    fi
}

# The view cells' PVS database of the default city at the default settings
# (occu-preprocess view-cells, about 7 minutes on this machine), made once
# into build/occluders/ and again when occu-preprocess changes (its path on
# stdout).
pvs_db() {
    local dir=$OCCU_ROOT/build/occluders
    local file=$dir/view-cells.pvs
    if [ ! -f "$file" ] || [ "$OCCU_ROOT/build/demos/occu-preprocess" -nt "$file" ]; then
        mkdir -p "$dir"
        "$OCCU_ROOT/build/demos/occu-preprocess" view-cells --out "$file.tmp" >&2
        mv "$file.tmp" "$file"
    fi
    echo "$file"
}

# The walkthrough's arguments that give pvs its database, when STRATEGIES
# (comma-separated) hold pvs without one.
pvs_args() {
    if [[ ,$1 =~ ,pvs[,:]|,pvs$ ]] && [[ $1 != *pvs-database* ]]; then
        echo "--set pvs-database=$(pvs_db)"
    fi
}
