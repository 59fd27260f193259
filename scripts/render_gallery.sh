#!/usr/bin/env bash
# Renders every examples/*.l to OUTDIR/<name>.png (800x800), the developmental figures
# also to OUTDIR/<name>.gif (animations), and writes OUTDIR/index.md, a markdown table of
# thumbnails with the figure names.
#
#   scripts/render_gallery.sh GRAFTAL_EXE OUTDIR
#
# Prints one line per picture; exits non-zero if any render fails (after trying all).
set -uo pipefail

if [ $# -ne 2 ]; then
    echo "usage: $0 GRAFTAL_EXE OUTDIR" >&2
    exit 2
fi

exe=$1
outdir=$2
here=$(cd "$(dirname "$0")/.." && pwd)
examples="$here/examples"

if [ ! -x "$exe" ]; then
    echo "render_gallery: $exe is not an executable (build graftal first)" >&2
    exit 2
fi
shopt -s nullglob
files=("$examples"/*.l)
# Figure order (fig2.2 before fig2.13), whatever the locale.
if [ ${#files[@]} -gt 0 ]; then
    mapfile -t files < <(printf '%s\n' "${files[@]}" | LC_ALL=C sort -V)
fi
if [ ${#files[@]} -eq 0 ]; then
    echo "render_gallery: no examples in $examples" >&2
    exit 2
fi
mkdir -p "$outdir" || exit 2

# The caption of a picture: the first line of the file's leading /* */ comment, which every
# example keeps for its one-line title (the source follows on the next lines), e.g.
# "Fig 2.2 Generating a quadratic Koch island"; pfg data files have no comment and get a
# caption from their name.
caption() {
    local file=$1 name=$2 text
    text=$(head -n 1 "$file" | sed -n -e '/^\/\*/!q' -e 's|^/\*[[:space:]]*||' \
           -e 's|[[:space:]]*\*/.*$||' -e 's/[[:space:]]\+/ /g' -e 's/[[:space:]]*$//' -e p)
    if [ -n "$text" ]; then
        printf '%s' "$text"
    else
        case $name in
            fig3.11?-hogeweg-hesper)
                printf 'Fig 3.11%s L-system of Hogeweg and Hesper (pfg data file)' "${name:7:1}" ;;
            appendixA-pfg-example) printf 'Appendix A example data file (pfg)' ;;
            fig2.6-dragon-curve-pfg) printf 'Fig 2.6 The dragon curve, Fl/rF predecessors (pfg data file)' ;;
            *) printf '%s (pfg data file)' "$name" ;;
        esac
    fi
}

failed=0
rendered=0
index="$outdir/index.md"
{
    echo "# graftal gallery"
    echo
    echo "The example L-systems, rendered by \`scripts/render_gallery.sh\` from \`examples/*.l\`."
    echo "Most come from *Lindenmayer Systems, Fractals, and Plants* (Prusinkiewicz & Hanan;"
    echo "\"Fig\" and \"Sec\" are its figures and sections); others from *The Algorithmic"
    echo "Beauty of Plants* (\"ABOP\"), the SIGGRAPH '88 paper *Developmental Models of"
    echo "Herbaceous Plants*, lecture notes on L-systems and a paper on a 3D L-system viewer,"
    echo "as each caption says. L-systems whose strings draw nothing are shown as their"
    echo "derivation, one row of cells per step. Click a picture for the 800x800 image."
    echo
    echo "| picture | figure | file |"
    echo "| --- | --- | --- |"
} > "$index.tmp"

for file in "${files[@]}"; do
    name=$(basename "$file" .l)
    out="$outdir/$name.png"
    start=${EPOCHREALTIME:-0}
    # A cpfg model's view file beside it (same name, .v) is its second argument.
    view=()
    [ -f "${file%.l}.v" ] && view=("${file%.l}.v")
    if msg=$("$exe" render "$file" ${view[@]+"${view[@]}"} -o "$out" --size 800x800 2>&1) &&
        [ -s "$out" ]; then
        end=${EPOCHREALTIME:-0}
        printf 'ok    %-40s -> %s (%s s)\n' "$name.l" "$out" \
            "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')"
        rendered=$((rendered + 1))
        # The music examples' scores, audio and MIDI files are made after this loop.
        case $name in
            fig6.9-*music*) extra=" ([score]($name-score.png), [audio]($name.wav), [MIDI]($name.mid))" ;;
            sec6.3-*) extra=" ([MIDI]($name.mid))" ;;
            *) extra="" ;;
        esac
        printf '| [<img src="%s.png" width="160" alt="%s">](%s.png) | %s%s | `examples/%s.l` |\n' \
            "$name" "$name" "$name" "$(caption "$file" "$name")" "$extra" "$name" >> "$index.tmp"
    else
        printf 'FAIL  %-40s %s\n' "$name.l" "$(printf '%s' "$msg" | head -n 3 | tr '\n' ' ')"
        failed=$((failed + 1))
        printf '| (render failed) | %s | `examples/%s.l` |\n' \
            "$(caption "$file" "$name")" "$name" >> "$index.tmp"
    fi
done
# Fractal music (LSFP 6.3): Fig 6.9's score engraved by LilyPond and its audio (16 kHz mono
# keeps the WAV small), and the MIDI files of every music example.
for file in "$examples"/fig6.9-*music*.l "$examples"/sec6.3-*.l; do
    name=$(basename "$file" .l)
    outs=("$outdir/$name.mid")
    case $name in fig6.9-*) outs+=("$outdir/$name-score.png" "$outdir/$name.wav") ;; esac
    for out in "${outs[@]}"; do
        if msg=$("$exe" music "$file" -o "$out" --sample-rate 16000 2>&1) && [ -s "$out" ]; then
            printf 'ok    %-40s -> %s\n' "$name.l" "$out"
        else
            printf 'FAIL  %-40s %s\n' "$name.l" "$(printf '%s' "$msg" | head -n 3 | tr '\n' ' ')"
            failed=$((failed + 1))
        fi
    done
done

# Map L-systems (docs/maps.md) also in the other renderings their figures show: the
# default picture is the Siero interpretation at the file's derivation length.
map_renderings=(
    "fig5.2-cell-layer|b|--map-geometry relaxed"
    "fig5.2-cell-layer|c|--map-geometry spline"
    "fig5.3-phascum-leaf|a|--map-geometry relaxed -n 10"
    "fig5.3-phascum-leaf|b|--map-geometry spline -n 11"
    "fig5.3-phascum-leaf|c|--map-geometry spline -n 12"
)
for entry in "${map_renderings[@]}"; do
    IFS='|' read -r name variant options <<< "$entry"
    file="$examples/$name.l"
    [ -f "$file" ] || continue
    out="$outdir/$name-$variant.png"
    # shellcheck disable=SC2086  # the options are words
    if msg=$("$exe" render "$file" -o "$out" --size 800x800 $options 2>&1) && [ -s "$out" ]; then
        printf 'ok    %-40s -> %s\n' "$name.l ($variant)" "$out"
        rendered=$((rendered + 1))
        printf '| [<img src="%s.png" width="160" alt="%s">](%s.png) | %s (%s: `%s`) | `examples/%s.l` |\n' \
            "$name-$variant" "$name-$variant" "$name-$variant" "$(caption "$file" "$name")" \
            "$variant" "$options" "$name" >> "$index.tmp"
    else
        printf 'FAIL  %-40s %s\n' "$name.l ($variant)" "$(printf '%s' "$msg" | head -n 3 | tr '\n' ' ')"
        failed=$((failed + 1))
    fi
done

# Developmental figures as animations (graftal animate): one frame per step, the camera
# fixed on the grown plant; the raceme and the fern declare their modules' ages and grow
# between steps. Anabaena (Fig 1.4) draws nothing, so its derivation diagram grows a row
# each step. The signals of Fig 3.12 and 3.13 change no segment's drawing (reached and
# unreached segments look the same), so they are left out.
animations=(
    "fig1.4-anabaena --fps 2 --hold 2"
    "fig3.7-lily-of-the-valley --fps 4 --hold 2"
    "fig3.9-lychnis-3d --fps 6 --hold 2"
    "fig3.14a-acropetal-signal --fps 4 --hold 2"
    "fig3.14b-basipetal-flowering --fps 6 --hold 2"
    "fig3.15-mycelis-muralis --fps 4 --hold 2"
    "fig4.5-cordate-leaf --fps 4 --hold 2"
    "fig6.2-snake-kolam --fps 3 --hold 2"
    "siggraph-raceme-elongating-internodes --frames-per-step 4 --fps 16 --hold 2"
    "fig3.8-fern --frames-per-step 4 --fps 16 --hold 2"
)
{
    echo
    echo "## Development"
    echo
    echo "Developmental figures drawn step by step by \`graftal animate\` (400x400 GIFs; the"
    echo "raceme and the fern grow between steps from their declared module ages; Anabaena,"
    echo "whose string draws nothing, as its derivation diagram growing a row per step)."
    echo
    echo "| animation | figure | command |"
    echo "| --- | --- | --- |"
} >> "$index.tmp"
for entry in "${animations[@]}"; do
    read -r name options <<< "$entry"
    file="$examples/$name.l"
    out="$outdir/$name.gif"
    [ -f "$file" ] || continue
    start=${EPOCHREALTIME:-0}
    # shellcheck disable=SC2086  # the options are words
    if msg=$("$exe" animate "$file" -o "$out" --size 400x400 $options 2>&1) && [ -s "$out" ]; then
        end=${EPOCHREALTIME:-0}
        printf 'ok    %-40s -> %s (%s s)\n' "$name.l" "$out" \
            "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')"
        rendered=$((rendered + 1))
        printf '| [<img src="%s.gif" width="160" alt="%s">](%s.gif) | %s | `graftal animate examples/%s.l %s` |\n' \
            "$name" "$name" "$name" "$(caption "$file" "$name")" "$name" "$options" >> "$index.tmp"
    else
        printf 'FAIL  %-40s %s\n' "$name.l" "$(printf '%s' "$msg" | head -n 3 | tr '\n' ' ')"
        failed=$((failed + 1))
    fi
done
mv "$index.tmp" "$index"

echo "$rendered rendered, $failed failed; index: $index"
[ "$failed" -eq 0 ]
