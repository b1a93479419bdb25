// IR reader: parses the printer's text form back into a Module (ids preserved, so the round trip
// print -> read -> print is exact). Two passes per function: create, then resolve references.
#include <cctype>
#include <cstdlib>
#include <map>
#include <sstream>
#include <unordered_map>

#include "ir/text.h"

namespace fscript::ir {
namespace {

struct Cursor {
  std::string s;
  size_t i = 0;
  void ws() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  }
  bool eat(const std::string& t) {
    ws();
    if (s.compare(i, t.size(), t) != 0) return false;
    i += t.size();
    return true;
  }
  std::string word() {
    ws();
    size_t b = i;
    while (i < s.size() &&
           (std::isalnum(static_cast<unsigned char>(s[i])) || s[i] == '_' || s[i] == '.' || s[i] == '$' ||
            s[i] == '-' || s[i] == '+'))
      ++i;
    return s.substr(b, i - b);
  }
  bool done() {
    ws();
    return i >= s.size();
  }
};

struct PendingInst {
  Inst* inst;
  std::vector<uint32_t> args;
  std::vector<uint32_t> targets;
  std::string callee;
};

class Reader {
 public:
  explicit Reader(const std::string& text) {
    std::istringstream in(text);
    std::string l;
    while (std::getline(in, l)) lines_.push_back(l);
  }

  std::unique_ptr<Module> run(std::string& error) {
    mod_ = std::make_unique<Module>();
    for (ln_ = 0; ln_ < lines_.size() && err_.empty(); ++ln_) {
      Cursor c{lines_[ln_]};
      if (c.done()) continue;
      if (c.eat("global @")) mod_->globals.push_back(c.word());
      else if (c.eat("garray @")) mod_->arrays.push_back(c.word());
      else if (c.eat("fn @")) function(c);
      else fail("expected 'global', 'garray' or 'fn'");
    }
    if (err_.empty()) resolve_calls();
    if (!err_.empty()) {
      error = err_;
      return nullptr;
    }
    return std::move(mod_);
  }

 private:
  void fail(const std::string& msg) {
    if (err_.empty()) err_ = "line " + std::to_string(ln_ + 1) + ": " + msg;
  }

  uint32_t number(Cursor& c, char prefix) {
    c.ws();
    if (c.i >= c.s.size() || c.s[c.i] != prefix) {
      fail(std::string("expected '") + prefix + "N'");
      return 0;
    }
    ++c.i;
    return count(c.word(), prefix == 'v' ? "value number" : "block number");
  }

  // A count or an id: digits only, at most kMaxCount, so that a hostile "v99999999999" cannot make
  // the reader allocate gigabytes for its value table (found by the ir_reader fuzz target).
  static constexpr uint32_t kMaxCount = 1u << 22;
  uint32_t count(const std::string& w, const char* what) {
    if (w.empty() || w.size() > 8 || w.find_first_not_of("0123456789") != std::string::npos) {
      fail(std::string("bad ") + what + " '" + w + "'");
      return 0;
    }
    uint32_t n = static_cast<uint32_t>(std::strtoul(w.c_str(), nullptr, 10));
    if (n > kMaxCount) {
      fail(std::string(what) + " " + w + " is over the reader's limit of " + std::to_string(kMaxCount));
      return 0;
    }
    return n;
  }

  void function(Cursor& c) {
    auto fn = std::make_unique<Function>();
    fn->name = c.word();
    if (!c.eat("(")) return fail("expected '('");
    fn->num_params = count(c.word(), "parameter count");
    if (!c.eat(")") || !c.eat("->")) return fail("expected ') ->'");
    fn->num_results = count(c.word(), "result count");
    fn->recursive = c.eat("recursive");
    fn->kernel = c.eat("kernel");
    if (c.eat("rows")) fn->row_params_from = count(c.word(), "row parameter");
    if (!err_.empty()) return;
    if (c.eat("ranges")) {
      size_t k = fn->num_params > fn->row_params_from ? fn->num_params - fn->row_params_from : 0;
      for (size_t i = 0; i < kNumParamBounds * k; ++i) {
        if (c.done()) return fail("expected " + std::to_string(kNumParamBounds * k) + " parameter ranges");
        ParamRange r;
        r.lo = std::strtof(c.word().c_str(), nullptr);
        r.hi = std::strtof(c.word().c_str(), nullptr);
        r.nan = c.word() == "nan";
        fn->row_param_ranges.push_back(r);
      }
    }
    if (!c.eat("{")) return fail("expected '{'");
    Function* f = fn.get();
    mod_->functions.push_back(std::move(fn));
    body(*f);
  }

  Block* block_for(Function& fn, uint32_t id) {
    auto it = blocks_.find(id);
    if (it != blocks_.end()) return it->second;
    Block* b = fn.add_block();
    b->id = id;
    fn.next_block = std::max(fn.next_block, id + 1);
    blocks_[id] = b;
    return b;
  }

  void body(Function& fn) {
    blocks_.clear();
    std::vector<PendingInst> pending;
    std::vector<Block*> order;
    Block* cur = nullptr;
    for (++ln_; ln_ < lines_.size() && err_.empty(); ++ln_) {
      Cursor c{lines_[ln_]};
      if (c.done()) continue;
      if (c.eat("}")) break;
      if (c.eat("array %")) {
        fn.arrays.push_back(c.word());
        continue;
      }
      if (c.s[c.i] == 'b' && c.i + 1 < c.s.size() && std::isdigit(static_cast<unsigned char>(c.s[c.i + 1]))) {
        cur = block_for(fn, number(c, 'b'));
        order.push_back(cur);
        if (!c.eat(":")) fail("expected ':' after block label");
        continue;
      }
      if (!cur) return fail("instruction before the first block label");
      pending.push_back(instruction(fn, c, cur));
    }
    if (!err_.empty()) return;
    // Layout follows the labels' order in the text.
    std::vector<std::unique_ptr<Block>> sorted;
    for (Block* b : order)
      for (auto& up : fn.blocks)
        if (up.get() == b) sorted.push_back(std::move(up));
    if (sorted.size() != fn.blocks.size()) return fail("branch to a block that has no label");
    fn.blocks = std::move(sorted);
    resolve(fn, pending);
  }

  PendingInst instruction(Function& fn, Cursor& c, Block* cur) {
    PendingInst p;
    uint32_t id = UINT32_MAX;
    if (c.s.compare(c.i, 1, "v") == 0) {
      id = number(c, 'v');
      if (!c.eat("=")) fail("expected '='");
    }
    std::string mn = c.word();
    int op = -1;
    for (int k = 0; k < kNumOps; ++k)
      if (mn == kOpInfo[k].mnemonic) op = k;
    if (op < 0) {
      fail("unknown op '" + mn + "'");
      return p;
    }
    Inst* i = fn.make(static_cast<Op>(op));
    i->block = cur;
    cur->insts.push_back(i);
    if (id != UINT32_MAX) {
      i->id = id;
      fn.next_value = std::max(fn.next_value, id + 1);
      if (values_.size() <= id) values_.resize(id + 1);
      values_[id] = i;
    } else {
      i->id = UINT32_MAX;  // renumbered below to a fresh id
    }
    p.inst = i;
    operands(fn, c, p);
    if (c.eat("!")) location(c, *i);
    if (!c.done()) fail("unexpected text after instruction");
    return p;
  }

  // "!LINE" or "!LINE:COL"
  void location(Cursor& c, Inst& i) {
    i.line = number(c.word());
    if (c.eat(":")) i.col = number(c.word());
  }
  uint32_t number(const std::string& w) {
    if (w.empty() || w.find_first_not_of("0123456789") != std::string::npos) fail("bad source position '!" + w + "'");
    return static_cast<uint32_t>(std::strtoul(w.c_str(), nullptr, 10));
  }

  void operands(Function& fn, Cursor& c, PendingInst& p) {
    Inst* i = p.inst;
    switch (i->op) {
      case Op::Const: i->imm = std::strtof(c.word().c_str(), nullptr); return;
      case Op::Param: i->aux = static_cast<int>(count(c.word(), "parameter index")); return;
      case Op::GLoad:
      case Op::GStore: {
        if (!c.eat("@")) return fail("expected '@global'");
        std::string g = c.word();
        i->aux = -1;
        for (size_t k = 0; k < mod_->globals.size(); ++k)
          if (mod_->globals[k] == g) i->aux = static_cast<int>(k);
        if (i->aux < 0) return fail("unknown global '@" + g + "'");
        if (i->op == Op::GStore && c.eat(",")) p.args.push_back(number(c, 'v'));
        return;
      }
      case Op::ANew:
      case Op::ALoad:
      case Op::AStore:
      case Op::ALen: {
        i->array_global = c.eat("@");
        if (!i->array_global && !c.eat("%")) return fail("expected an array");
        std::string a = c.word();
        const auto& table = i->array_global ? mod_->arrays : fn.arrays;
        i->aux = -1;
        for (size_t k = 0; k < table.size(); ++k)
          if (table[k] == a) i->aux = static_cast<int>(k);
        if (i->aux < 0) return fail("unknown array '" + a + "'");
        while (c.eat(",")) p.args.push_back(number(c, 'v'));
        return;
      }
      case Op::Call:
        if (!c.eat("@")) return fail("expected '@function'");
        p.callee = c.word();
        if (!c.eat("(")) return fail("expected '('");
        if (!c.eat(")")) {
          do p.args.push_back(number(c, 'v'));
          while (c.eat(","));
          if (!c.eat(")")) return fail("expected ')'");
        }
        return;
      case Op::Phi:
        do {
          if (!c.eat("[")) break;
          p.args.push_back(number(c, 'v'));
          if (!c.eat(",")) return fail("expected ','");
          p.targets.push_back(number(c, 'b'));
          if (!c.eat("]")) return fail("expected ']'");
        } while (c.eat(","));
        return;
      default: {
        bool first = true;
        while (!c.done() && c.s[c.i] != '!') {
          if (!first && !c.eat(",")) return fail("expected ','");
          first = false;
          c.ws();
          if (c.s[c.i] == 'v') p.args.push_back(number(c, 'v'));
          else p.targets.push_back(number(c, 'b'));
        }
        return;
      }
    }
  }

  void resolve(Function& fn, std::vector<PendingInst>& pending) {
    for (auto& p : pending) {
      for (uint32_t a : p.args) {
        if (a >= values_.size() || !values_[a]) return fail("use of undefined value v" + std::to_string(a));
        p.inst->args.push_back(values_[a]);
      }
      for (uint32_t t : p.targets) {
        if (!blocks_.count(t)) return fail("reference to unknown block b" + std::to_string(t));
        p.inst->targets.push_back(blocks_[t]);
      }
      if (!p.callee.empty()) calls_.push_back({p.inst, p.callee});
    }
    for (auto& p : pending)
      if (p.inst->id == UINT32_MAX) p.inst->id = fn.next_value++;
    for (auto& b : fn.blocks)
      for (Block* s : b->succs()) s->preds.push_back(b.get());
    values_.clear();
  }

  void resolve_calls() {
    for (auto& [inst, name] : calls_) {
      inst->aux = mod_->find_function(name);
      if (inst->aux < 0) return fail("call to unknown function '@" + name + "'");
    }
  }

  std::vector<std::string> lines_;
  size_t ln_ = 0;
  std::string err_;
  std::unique_ptr<Module> mod_;
  std::map<uint32_t, Block*> blocks_;
  std::vector<Inst*> values_;
  std::vector<std::pair<Inst*, std::string>> calls_;
};

}  // namespace

std::unique_ptr<Module> read(const std::string& text, std::string& error) { return Reader(text).run(error); }

}  // namespace fscript::ir
