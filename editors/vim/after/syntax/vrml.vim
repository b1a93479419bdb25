" FScript inside the script fields of FVRML nodes in .wrl files (definition, diffuseColor,
" operation, the FTransform's affine fields...), on top of Vim's own VRML syntax. The region starts
" at the quote (the field name is found by looking behind), so it wins over Vim's VRMLString there.
let s:saved = get(b:, "current_syntax", "")
unlet! b:current_syntax
syntax include @FScript syntax/fscript.vim
let b:current_syntax = s:saved

syntax region vrmlFScript matchgroup=vrmlFScriptQuote
      \ start=+\(\<\(definition\|diffuseColor\|operation\|translation\|rotation\|scale\|scaleOrientation\|center\|ambientIntensity\|emissiveColor\|shininess\|specularColor\|transparency\)\s\+\)\@<="+
      \ skip=+\\"+ end=+"+ contains=@FScript keepend
highlight default link vrmlFScriptQuote String
