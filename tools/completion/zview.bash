# bash completion for zview(1). Installed by `make install` as
# $(PREFIX)/share/bash-completion/completions/zview.
# Model formats come from `zview --formats`, so the list matches the
# build (with or without assimp). tests/test_options.c checks the options
# and their words against the option table (src/app/options.c).

_zview_formats()
{
    zview --formats 2>/dev/null | cut -d ' ' -f 1
    printf '%s\n' coff noff   # more names of OFF files
}

_zview()
{
    local cur prev words cword split=false
    if declare -F _init_completion >/dev/null 2>&1; then
        _init_completion -s || return
    else
        cur=${COMP_WORDS[COMP_CWORD]}
        prev=${COMP_WORDS[COMP_CWORD - 1]}
        if [[ $cur == --*=* ]]; then
            prev=${cur%%=*}
            cur=${cur#*=}
            split=true
        fi
    fi

    case $prev in
        --mode) COMPREPLY=($(compgen -W "half ascii braille sixel kitty iterm cells auto" -- "$cur")); return ;;
        --color | --colour) COMPREPLY=($(compgen -W "truecolor 256 16 8 none" -- "$cur")); return ;;
        --shade) COMPREPLY=($(compgen -W "lambert smooth depth id" -- "$cur")); return ;;
        --view) COMPREPLY=($(compgen -W "auto front back left right top bottom iso" -- "$cur")); return ;;
        --layout) COMPREPLY=($(compgen -W "row grid none" -- "$cur")); return ;;
        --order) COMPREPLY=($(compgen -W "file front-to-back back-to-front shuffle" -- "$cur")); return ;;
        --samples) COMPREPLY=($(compgen -W "1 4 9 16" -- "$cur")); return ;;
        -a | --algo) COMPREPLY=($(compgen -W "zbuffer scanline span hzb hzb-octree all" -- "$cur")); return ;;
        --up) COMPREPLY=($(compgen -W "y z x -y -z -x" -- "$cur")); return ;;
        --image-format) COMPREPLY=($(compgen -W "png ppm" -- "$cur")); return ;;
        --bg) COMPREPLY=($(compgen -W "default black white grey" -- "$cur")); return ;;
        --show) COMPREPLY=($(compgen -W "both a b heat" -- "$cur")); return ;;
        --unit) COMPREPLY=($(compgen -W "mm in m" -- "$cur")); return ;;
        --format) COMPREPLY=($(compgen -W "$(_zview_formats) assimp" -- "$cur")); return ;;
        --repair)
            # --repair=STEPS: a comma list; --repair IN: the model (below)
            if $split; then
                local done=
                [[ $cur == *,* ]] && done=${cur%,*},
                COMPREPLY=($(compgen -P "$done" -W "weld clean manifold winding holes all" -- "${cur##*,}"))
                compopt -o nospace 2>/dev/null
                return
            fi ;;
        -o | --output | --dump-ids | --dump-screen)
            COMPREPLY=($(compgen -f -- "$cur"))
            return ;;
        -s | --size | --yaw | --pitch | --roll | --zoom | --pan | --fit-from | --move | --turn | \
            --scale | --persp | --grid | --max-polys | --max-memory | --views | -j | --threads | --fps | --max-rate | --crease | \
            --light | --ambient | --turntable | --point-size | --line-width | --contrast | --problem | --section | --max-locations | --weld | --max-hole | --tolerance | \
            --bed | --min-thickness | --measure | --overhang | --marks | --preview)
            return ;;
    esac
    $split && return

    if [[ $cur == -* && $cur != - ]]; then
        COMPREPLY=($(compgen -W "--help --version --print --output --size --mode --color --shade
            --info --check --dump-ids --dump-screen --algo --yaw --pitch --roll --zoom --pan --fit-from
            --move --turn --scale --persp --ortho --cull --grid --max-polys --bench --bench-tty
            --views --threads --json --fps --max-rate --format --formats --up --flip --image-format --sketch
            --samples --crease --light --ambient --view --layout --edges --order --print-view
            --turntable --point-size --line-width --wireframe --points --strict --no-sandbox --max-memory --bg --contrast --no-textures
            --problems --problem --section --max-locations --parts --watch --repair --weld --max-hole --diff --tolerance --show --quiet --textconv
            --bed --unit --overhang --thickness --min-thickness --measure --marks --preview" -- "$cur"))
        [[ ${COMPREPLY-} == *= ]] && compopt -o nospace 2>/dev/null
        return
    fi

    # model files: folders, and files of the extensions this build reads
    local IFS=$'\n' ext f
    local exts=$(_zview_formats)
    COMPREPLY=($(compgen -d -- "$cur"))
    for f in $(compgen -f -- "$cur"); do
        [[ -d $f ]] && continue
        ext=${f##*.}
        ext=${ext,,}
        [[ $f == *.* ]] && grep -qxF -- "$ext" <<<"$exts" && COMPREPLY+=("$f")
    done
    compopt -o filenames 2>/dev/null
}

complete -F _zview zview
