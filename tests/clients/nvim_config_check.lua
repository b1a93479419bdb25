-- Opened by lsp_nvim_test.sh after editors/nvim/lua/fscript.lua: waits for the server's diagnostics on
-- the current buffer, prints the filetype, the attached client and the first message, then sends
-- the requests in QUERIES ("method@line:character;...", 0-based) through Neovim's client and
-- prints each result as JSON.
local ok = vim.wait(15000, function() return #vim.diagnostic.get(0) > 0 end, 50)
local names = {}
for _, c in pairs(vim.lsp.buf_get_clients(0)) do table.insert(names, c.name) end
io.stdout:write("filetype=" .. vim.bo.filetype .. " clients=" .. table.concat(names, ",") .. " diagnostic=" ..
                (ok and vim.diagnostic.get(0)[1].message or "none") .. "\n")
if vim.fn.exists(":FvrmlPreview") == 2 then io.stdout:write("command FvrmlPreview\n") end
for query in string.gmatch(os.getenv("QUERIES") or "", "[^;]+") do
  if query == "preview" then  -- what :FvrmlPreview asks, answered synchronously
    local params = { command = "fscript.preview", arguments = { vim.uri_from_bufnr(0) } }
    for _, reply in pairs(vim.lsp.buf_request_sync(0, "workspace/executeCommand", params, 15000) or {}) do
      io.stdout:write("fscript.preview => " .. vim.fn.json_encode(reply.result or reply.error or vim.NIL) .. "\n")
    end
    goto continue
  end
  if query == "profile" then  -- :FscriptProfile, then the lenses Neovim's own code-lens support holds
    vim.cmd("FscriptProfile")
    vim.wait(30000, function() return #(vim.lsp.codelens.get(0) or {}) > 1 end, 50)
    for _, l in ipairs(vim.lsp.codelens.get(0) or {}) do
      io.stdout:write("codelens " .. l.range.start.line .. ": " .. (l.command and l.command.title or "") .. "\n")
    end
    goto continue
  end
  local method, line, character = string.match(query, "^([^@]+)@(%d+):(%d+)$")
  local params = { textDocument = vim.lsp.util.make_text_document_params(),
                   position = { line = tonumber(line), character = tonumber(character) } }
  local replies = vim.lsp.buf_request_sync(0, method, params, 10000) or {}
  for _, reply in pairs(replies) do
    io.stdout:write(method .. " => " .. vim.fn.json_encode(reply.result or reply.error or vim.NIL) .. "\n")
  end
  ::continue::
end
vim.cmd("qa!")
