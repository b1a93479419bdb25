" Vim syntax file for FScript, the float-only JavaScript subset of FVRML (highlighting for
" editors that do not use the language server's semantic tokens). The keywords and built-ins are
" the compiler's own (frontend/fscript/tokens.def, builtins.def); editors/check_grammars.py keeps
" this list in step with them.
if exists("b:current_syntax")
  finish
endif

syntax keyword fscriptKeyword function return if else for while do break continue var let const new
syntax keyword fscriptBoolean true false
syntax keyword fscriptBuiltin abs fabs sqrt exp log log10 sin cos tan asin acos atan atan2 hypot
syntax keyword fscriptBuiltin sinh cosh tanh ceil floor round max min mod pow sign clamp noise
syntax keyword fscriptConstant pi
syntax keyword fscriptEntry FRep parametric_x parametric_y parametric_z parametric_r parametric_g parametric_b
syntax keyword fscriptInput x y z u v w t r g b
syntax match fscriptNumber "\<\d\+\(\.\d*\)\=\([eE][+-]\=\d\+\)\=\>"
syntax match fscriptNumber "\.\d\+\([eE][+-]\=\d\+\)\=\>"
syntax match fscriptOperator "[-+*/%^=<>!&|?:]"
syntax region fscriptString start=+"+ skip=+\\"+ end=+"+ oneline
syntax region fscriptString start=+'+ skip=+\\'+ end=+'+ oneline
syntax keyword fscriptTodo TODO FIXME XXX contained
syntax match fscriptComment "//.*$" contains=fscriptTodo
syntax region fscriptComment start="/\*" end="\*/" contains=fscriptTodo

highlight default link fscriptKeyword Keyword
highlight default link fscriptBoolean Boolean
highlight default link fscriptBuiltin Function
highlight default link fscriptConstant Constant
highlight default link fscriptEntry Identifier
highlight default link fscriptInput Special
highlight default link fscriptNumber Number
highlight default link fscriptOperator Operator
highlight default link fscriptString String
highlight default link fscriptTodo Todo
highlight default link fscriptComment Comment

let b:current_syntax = "fscript"
