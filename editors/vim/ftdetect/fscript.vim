" FScript files: *.fs (FScript, not F# or Forth, once this folder is on 'runtimepath').
autocmd BufRead,BufNewFile *.fs set filetype=fscript
