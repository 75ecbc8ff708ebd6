#!/bin/sh
# `make mutate`: do the tests catch errors, not only changes? Plants one realistic bug at a time
# in a copy of the sources (each a one-line change a person could make), builds, runs the test
# suite and reports whether some test failed ("caught") or none did ("SURVIVED"). A bug that
# survives names a test to write. Usage: tools/mutate.sh [NAME-FILTER]; takes about a minute per
# mutation on 2 cores. Exit 1 when any planted bug survives.
set -u
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
filter=${1:-}

# name | file | sed expression (must change the file) | what it breaks
cat > "$work/list" <<'EOF'
shadow-one-sided|src/render/tracer.c|s/if (!q->shadow \&\& !(p->flags \& RF_PRIM_TWO_SIDED)) {/if (!(p->flags \& RF_PRIM_TWO_SIDED)) {/|shadow rays skip the back of one-sided surfaces
edge-fallback|src/geom/intersect.c|s/return fma(px, qy, -a) - fma(py, qx, -b);/return 0.0;/|the watertight edge test without its exact fallback
srgb-threshold|src/color/transfer.c|s/if (v <= 0.0031308)/if (v <= 0.031308)/|the sRGB curve's linear segment ends too late
normal-transpose|src/scene/scene.c|s/in.normal_to_world = rf_mat3_transpose(lin_inv);/in.normal_to_world = lin_inv;/|normals of instances by M^-1 instead of its transpose
tir-light|src/render/kernel_body.h|s/wr = fresnel ? rf_rgb_add(wr, wt) : rf_rgb_add(wr, kt);/wr = wr;/|total internal reflection loses the transmitted share
slab-unwidened|src/geom/bvh_trace.c|s/float near = fi \* (1.0f - 0x1p-21f), far = fi \* (1.0f + 0x1p-21f);/float near = fi, far = fi;/; s/float up = rf__widen_up(o\[a\]), down = rf__widen_down(o\[a\]);/float up = (float)o[a], down = up;/|the BVH slab test without its outward rounding of 1/d and of the origin
phong-exponent|src/render/kernel_body.h|s/pow(rv, m->shininess)/pow(rv, m->shininess + 1.0)/|the Phong exponent off by one
fresnel-swapped|src/render/kernel_body.h|s/fr = f.r;/fr = f.t;/|Fresnel's reflected and transmitted weights swapped
falloff-linear|src/render/kernel_body.h|s#1.0 / (d \* d)#1.0 / d#|point lights fall off with 1/d instead of 1/d^2
snell-inverted|src/render/kernel_body.h|s/double eta_i = h.front ? 1.0 : m->ior, eta_t = h.front ? m->ior : 1.0;/double eta_i = h.front ? m->ior : 1.0, eta_t = h.front ? 1.0 : m->ior;/|refraction enters with the inverse index
tie-rule|src/render/tracer.c|s/key < key_lim ? nextafter/key > key_lim ? nextafter/|of two hits at the same t the higher key wins
area-cos|src/render/kernel_body.h|s/double cos_l = -rf_vec3_dot(l->direction, ls->l);/double cos_l = 1.0;/|area lights without the cosine at the light
motion-reversed|src/scene/scene.c|s/steps\[i\].v\[j\] = (1.0 - s) \* mo->steps\[k\]\[i\].v\[j\] + s \* mo->steps\[k + 1\]\[i\].v\[j\];/steps[i].v[j] = s * mo->steps[k][i].v[j] + (1.0 - s) * mo->steps[k + 1][i].v[j];/|keyframes interpolated backwards
EOF

# one snapshot of the sources (committed files as they are in the working tree) and of the
# build, taken now: edits made while this runs do not leak into later mutations
mkdir -p "$work/src"
(cd "$root" && git ls-files -z | xargs -0 -I{} cp -p --parents {} "$work/src/") 2>/dev/null
cp -a "$root/build" "$work/src/build" 2>/dev/null   # times kept: make rebuilds what is stale, then only the mutated file
(cd "$work/src" && make -j2 build/refray build/refray-tests build/refray-raster build/refray-verify >/dev/null 2>&1) ||
    { echo "the sources do not build"; exit 1; }
# the suite as it is: a mutation is caught only by a test that passes here
(cd "$work/src" && RF_TEST_DATA=tests/data timeout 1200 build/refray-tests 2>&1) | sed -n 's/^FAIL \([^ ]*\) .*/\1/p' | sort -u > "$work/base_fails"
[ -s "$work/base_fails" ] && echo "(failing before any mutation, not counted: $(tr '\n' ' ' < "$work/base_fails"))"

survived=0
total=0
while IFS='|' read -r name file expr what; do
    [ -n "$filter" ] && case $name in *"$filter"*) ;; *) continue ;; esac
    total=$((total + 1))
    cp "$work/src/$file" "$work/orig"
    sed -i "$expr" "$work/src/$file"
    if cmp -s "$work/orig" "$work/src/$file"; then
        printf "%-18s NOT APPLIED (the line changed: update tools/mutate.sh)  %s\n" "$name" "$what"
        survived=$((survived + 1))
        continue
    fi
    touch "$work/src/$file"
    if ! (cd "$work/src" && make -j2 build/refray build/refray-tests build/refray-raster build/refray-verify >/dev/null 2>&1); then
        printf "%-18s DOES NOT BUILD (fix the expression in tools/mutate.sh)  %s\n" "$name" "$what"
        survived=$((survived + 1))
        cp "$work/orig" "$work/src/$file"
        continue
    fi
    (cd "$work/src" && RF_TEST_DATA=tests/data timeout 1200 build/refray-tests 2>&1) |
        sed -n 's/^FAIL \([^ ]*\) .*/\1/p' | sort -u > "$work/fails"
    cp "$work/orig" "$work/src/$file" # back to the original (a new mtime: it rebuilds next time)
    caught=$(comm -23 "$work/fails" "$work/base_fails" | tr '\n' ' ')
    if [ -z "$caught" ]; then
        printf "%-18s SURVIVED  %s\n" "$name" "$what"
        survived=$((survived + 1))
    else
        printf "%-18s caught    %s  (by: %s)\n" "$name" "$what" "$caught"
    fi
done < "$work/list"
echo "$((total - survived)) of $total planted bugs caught"
[ "$survived" = 0 ]
