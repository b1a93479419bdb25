#!/usr/bin/env bash
# Every `--stats` field, with its meaning checked.
# usage: stats.sh FSCRIPT SOURCE_DIR FVRML_RUN FVRML_MESHDIFF
set -u
. "$(dirname "$0")/feature.sh"

# ---- Every --stats field ----
jcheck "--stats fields of a single run" err "
set(j) == {'compile_ms', 'dual_contouring', 'evaluation_ms', 'ftransforms', 'huge_heap_mib', 'parse_ms', 'polygonize_ms', 'prune', 'row_split', 'shape_diagnostics', 'shape_diagnostics_ms', 'shapes', 'tiers', 'write_ms'} and
set(j['dual_contouring']) == {'max_qef_error_cells', 'merged_cells', 'normals', 'shapes', 'triangles', 'vertices'} and
set(j['prune']) == {'evaluated', 'evaluated_fraction', 'fallbacks', 'levels', 'local_tapes', 'points', 'pruned'} and
set(j['prune']['local_tapes']) == {'regions', 'simplified', 'mean_ops', 'full_ops', 'gradient_tapes'} and
j['prune']['pruned'] and j['prune']['points'] == 512 and j['prune']['fallbacks'] == 0 and
[l['size'] for l in j['prune']['levels']] == [64, 32, 16, 8] and
all(j[k] >= 0 for k in ('compile_ms', 'evaluation_ms', 'parse_ms', 'polygonize_ms', 'write_ms')) and j['evaluation_ms'] > 0 and
set(j['shapes'][0]) == {'active', 'domain', 'fraction', 'frames', 'geometry', 'kind', 'line', 'resolution', 'transform', 'triangles', 'vertices'} and
j['shape_diagnostics'] == [] and j['shape_diagnostics_ms'] >= 0 and
j['shapes'][0]['kind'] == 'implicit' and j['shapes'][0]['line'] == 2 and j['shapes'][0]['resolution'] == [8, 8, 8] and
j['shapes'][0]['domain'] == [-1, 1, -1, 1, -1, 1] and j['shapes'][0]['triangles'] > 0 and
j['shapes'][0]['vertices'] >= j['dual_contouring']['vertices'] and
j['dual_contouring']['vertices'] * 2 - 4 == j['dual_contouring']['triangles'] == j['shapes'][0]['triangles'] and
set(j['shapes'][0]['geometry']) == {'field', 't', 'timeSpan'}
" -- "$R" "$T/ball.wrl" --stats -o "$T/b.ply"
jcheck "--stats fields of an FTransform" err "
set(j['ftransforms'][0]) == {'affine', 'fraction', 'ftransforms', 'operation', 'parent', 'shapes', 'type'} and
j['ftransforms'][0]['type'] == 'analytical' and j['ftransforms'][0]['shapes'] == [0, 1] and j['ftransforms'][0]['parent'] == -1 and
all(s['ftransform'] == 0 for s in j['shapes'])
" -- "$R" "$P/listing1-operation.wrl" --stats
jcheck "--stats fields of animated output" err "
set(j['animations'][0]) == {'bytes_per_triangle', 'cache_bytes', 'constant', 'frames', 'line', 'triangles'} and
j['animations'][0]['frames'] == 4 and not j['animations'][0]['constant'] and
near(j['animations'][0]['bytes_per_triangle'], j['animations'][0]['cache_bytes'] / j['animations'][0]['triangles'])
" -- "$R" "$P/figure1-morphing.wrl" --frames 4 -o "$T/a.wrl" --stats --resolution-scale 0.3
jcheck "--stats fields of numbered frames" err "
[f['fraction'] for f in j['frames']] == [0, 0.5] and all(f['triangles'] > 0 and f['vertices'] > 0 for f in j['frames'])
" -- "$R" "$P/figure1-morphing.wrl" --frames 2 -o "$T/fr.ply" --stats --resolution-scale 0.3

finish stats
