-- Opened by lsp_nvim_test.sh after editors/nvim/fscript.lua: waits for the server's diagnostics on
-- the current buffer and prints the filetype, the first message, and the client's name.
local ok = vim.wait(15000, function() return #vim.diagnostic.get(0) > 0 end, 50)
local names = {}
for _, c in pairs(vim.lsp.buf_get_clients(0)) do table.insert(names, c.name) end
io.stdout:write("filetype=" .. vim.bo.filetype .. " clients=" .. table.concat(names, ",") .. " diagnostic=" ..
                (ok and vim.diagnostic.get(0)[1].message or "none") .. "\n")
vim.cmd("qa!")
