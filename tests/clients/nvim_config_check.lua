-- Opened by lsp_nvim_test.sh after editors/nvim/fscript.lua: waits for the server's diagnostics on
-- the current buffer, prints the filetype, the attached client and the first message, then sends
-- the requests in QUERIES ("method@line:character;...", 0-based) through Neovim's client and
-- prints each result as JSON.
local ok = vim.wait(15000, function() return #vim.diagnostic.get(0) > 0 end, 50)
local names = {}
for _, c in pairs(vim.lsp.buf_get_clients(0)) do table.insert(names, c.name) end
io.stdout:write("filetype=" .. vim.bo.filetype .. " clients=" .. table.concat(names, ",") .. " diagnostic=" ..
                (ok and vim.diagnostic.get(0)[1].message or "none") .. "\n")
for query in string.gmatch(os.getenv("QUERIES") or "", "[^;]+") do
  local method, line, character = string.match(query, "^([^@]+)@(%d+):(%d+)$")
  local params = { textDocument = vim.lsp.util.make_text_document_params(),
                   position = { line = tonumber(line), character = tonumber(character) } }
  local replies = vim.lsp.buf_request_sync(0, method, params, 10000) or {}
  for _, reply in pairs(replies) do
    io.stdout:write(method .. " => " .. vim.fn.json_encode(reply.result or reply.error or vim.NIL) .. "\n")
  end
end
vim.cmd("qa!")
