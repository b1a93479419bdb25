-- Neovim (0.7 or later) set-up for FScript: *.fs files are FScript (not F#), and fscript-lsp
-- serves them and .wrl scenes (the FScript strings inside). Use, from init.lua:
--   vim.opt.runtimepath:append("/path/to/editors/nvim")
--   require("fscript")
-- or `:luafile /path/to/editors/nvim/lua/fscript.lua` from init.vim. FSCRIPT_LSP may name the
-- server's path.
local server = os.getenv("FSCRIPT_LSP") or "fscript-lsp"

vim.cmd([[
  augroup fscript_filetypes
    autocmd!
    autocmd BufRead,BufNewFile *.fs setlocal filetype=fscript
    autocmd BufRead,BufNewFile *.wrl setlocal filetype=vrml
  augroup END
]])

local clients = {}  -- one server per root folder

local function attach(bufnr)
  local file = vim.api.nvim_buf_get_name(bufnr)
  local root = vim.fn.fnamemodify(file, ":p:h")
  if not clients[root] then
    clients[root] = vim.lsp.start_client({
      name = "fscript-lsp",
      cmd = { server },
      root_dir = root,
    })
  end
  if clients[root] then vim.lsp.buf_attach_client(bufnr, clients[root]) end
end

function _G.fscript_lsp_attach() attach(vim.api.nvim_get_current_buf()) end

vim.cmd([[
  augroup fscript_lsp
    autocmd!
    autocmd FileType fscript,vrml lua fscript_lsp_attach()
  augroup END
]])

-- FScript comments and indentation like JavaScript's.
vim.cmd([[
  augroup fscript_buffer
    autocmd!
    autocmd FileType fscript setlocal commentstring=//\ %s shiftwidth=2 expandtab
  augroup END
]])

-- :FvrmlPreview: the server starts `fvrml-run SCENE --serve` for this buffer (fscript.preview) and
-- answers with the page's URL, opened in the browser; the page follows every :w.
vim.api.nvim_create_user_command("FvrmlPreview", function()
  local bufnr = vim.api.nvim_get_current_buf()
  local params = { command = "fscript.preview", arguments = { vim.uri_from_bufnr(bufnr) } }
  vim.lsp.buf_request(bufnr, "workspace/executeCommand", params, function(err, result)
    if err or not result then
      vim.notify("FvrmlPreview: " .. (err and err.message or "no answer"), vim.log.levels.ERROR)
      return
    end
    vim.notify("FVRML preview: " .. result.url)
    if vim.ui.open then vim.ui.open(result.url) else vim.fn.jobstart({ "xdg-open", result.url }, { detach = true }) end
  end)
end, { desc = "FVRML: the live preview of this scene in the browser" })

-- :FscriptProfile: the server meshes this buffer's shapes with a profiler (fscript.profile) and the
-- code lenses show each line's share of the evaluation time and operations, and of the points whose
-- tape still runs it. Nothing is profiled until asked; an edit takes the line lenses away.
vim.api.nvim_create_user_command("FscriptProfile", function()
  local bufnr = vim.api.nvim_get_current_buf()
  local params = { command = "fscript.profile", arguments = { vim.uri_from_bufnr(bufnr) } }
  vim.lsp.buf_request(bufnr, "workspace/executeCommand", params, function(err)
    if err then
      vim.notify("FscriptProfile: " .. err.message, vim.log.levels.ERROR)
      return
    end
    vim.lsp.codelens.refresh()
  end)
end, { desc = "FScript: each line's share of the evaluation cost, as code lenses" })

return { server = server }
