#include "test_export_usda_reader.h"

#include <cctype>
#include <charconv>
#include <fstream>
#include <set>
#include <sstream>

namespace throng::test::usda {
namespace {

// Value types and their tuple arity (0: a scalar number, -1: a string).
const std::map<std::string, int> value_types{
    {"int", 0}, {"int64", 0}, {"float", 0}, {"double", 0}, {"half", 0}, {"float3", 3}, {"point3f", 3},
    {"color3f", 3}, {"quath", 4}, {"quatf", 4}, {"string", -1}, {"token", -1}};
const std::set<std::string> integer_types{"int", "int64"};

struct Token {
  enum Kind { word, number, string, punct, path, end } kind;
  std::string text;
  int line;
};

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  if (text.rfind("#usda 1.0\n", 0) != 0) throw SyntaxError("line 1: expected the header '#usda 1.0'");
  i = 10;
  line = 2;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') { ++line; ++i; continue; }
    if (c == ' ' || c == '\t') { ++i; continue; }
    if (c == '#') { while (i < text.size() && text[i] != '\n') ++i; continue; }
    if (c == '"') {
      std::string s;
      ++i;
      while (i < text.size() && text[i] != '"') {
        if (text[i] == '\n') throw SyntaxError("line " + std::to_string(line) + ": line break inside a string");
        if (text[i] == '\\') {
          ++i;
          if (i >= text.size()) break;
          s += text[i] == 'n' ? '\n' : text[i];
        } else {
          s += text[i];
        }
        ++i;
      }
      if (i >= text.size()) throw SyntaxError("line " + std::to_string(line) + ": unterminated string");
      ++i;
      tokens.push_back({Token::string, s, line});
      continue;
    }
    if (c == '<') {
      const std::size_t close = text.find('>', i);
      if (close == std::string::npos) throw SyntaxError("line " + std::to_string(line) + ": unterminated path");
      tokens.push_back({Token::path, text.substr(i + 1, close - i - 1), line});
      i = close + 1;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') {
      std::size_t j = i + 1;
      while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.' || text[j] == 'e' ||
                                 text[j] == 'E' || ((text[j] == '-' || text[j] == '+') && (text[j - 1] == 'e' || text[j - 1] == 'E')))) {
        ++j;
      }
      tokens.push_back({Token::number, text.substr(i, j - i), line});
      i = j;
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i + 1;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_' || text[j] == ':' || text[j] == '.')) ++j;
      tokens.push_back({Token::word, text.substr(i, j - i), line});
      i = j;
      continue;
    }
    if (std::string("()[]{}=,:").find(c) != std::string::npos) {
      tokens.push_back({Token::punct, std::string(1, c), line});
      ++i;
      continue;
    }
    throw SyntaxError("line " + std::to_string(line) + ": unexpected character '" + std::string(1, c) + "'");
  }
  tokens.push_back({Token::end, "", line});
  return tokens;
}

class Parser {
 public:
  explicit Parser(std::vector<Token> tokens) : tokens_(std::move(tokens)) {}

  Layer layer() {
    Layer l;
    if (accept("(")) {
      while (!accept(")")) {
        const std::string key = expect_word();
        expect("=");
        if (key == "customLayerData") {
          expect("{");
          while (!accept("}")) {
            const std::string type = expect_word();
            const std::string name = expect_kind(Token::string);
            expect("=");
            l.custom_layer_data[name] = {type, value(type)};
          }
        } else {
          l.metadata[key] = scalar_text();
        }
      }
    }
    while (peek().kind != Token::end) l.prims.push_back(prim(""));
    return l;
  }

 private:
  const Token& peek() const { return tokens_[pos_]; }
  [[noreturn]] void fail(const std::string& what) const {
    throw SyntaxError("line " + std::to_string(peek().line) + ": expected " + what + ", found '" + peek().text + "'");
  }
  bool accept(const std::string& punct) {
    if (peek().kind == Token::punct && peek().text == punct) { ++pos_; return true; }
    return false;
  }
  void expect(const std::string& punct) {
    if (!accept(punct)) fail("'" + punct + "'");
  }
  std::string expect_kind(Token::Kind kind) {
    if (peek().kind != kind) fail(kind == Token::string ? "a string" : kind == Token::word ? "a name" : "a value");
    return tokens_[pos_++].text;
  }
  std::string expect_word() { return expect_kind(Token::word); }

  // A number of the given storage precision, as USD stores the text: float types parse to the nearest float,
  // half types to the nearest double and then half, integers refuse a fraction or an exponent.
  enum class Storage { integer, half, single, twice };
  double number(Storage storage) {
    if (peek().kind != Token::number) fail(storage == Storage::integer ? "an integer" : "a number");
    const std::string& t = tokens_[pos_].text;
    const char* first = t.data() + (t[0] == '+' ? 1 : 0);
    double v = 0;
    std::from_chars_result r{};
    if (storage == Storage::single) {
      float f = 0;
      r = std::from_chars(first, t.data() + t.size(), f);
      v = f;
    } else {
      r = std::from_chars(first, t.data() + t.size(), v);
      if (storage == Storage::half) v = to_half(v);
    }
    if (r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("a number");
    if (storage == Storage::integer && t.find_first_of(".eE") != std::string::npos) fail("an integer");
    ++pos_;
    return v;
  }

  // One element of `type` (without []) appended to `out`.
  void element(const std::string& type, Value& out) {
    const auto it = value_types.find(type);
    if (it == value_types.end()) throw SyntaxError("line " + std::to_string(peek().line) + ": unknown value type '" + type + "'");
    const int arity = it->second;
    const Storage storage = integer_types.count(type) ? Storage::integer
                            : type == "double"          ? Storage::twice
                            : type.find('h') != std::string::npos ? Storage::half  // half, quath
                                                        : Storage::single;
    if (arity < 0) {
      out.strings.push_back(expect_kind(Token::string));
    } else if (arity == 0) {
      out.numbers.push_back(number(storage));
    } else {
      expect("(");
      for (int k = 0; k < arity; ++k) {
        if (k) expect(",");
        out.numbers.push_back(number(storage));
      }
      expect(")");
    }
    ++out.elements;
  }

  Value value(const std::string& declared) {
    Value v;
    const bool array = declared.size() > 2 && declared.compare(declared.size() - 2, 2, "[]") == 0;
    const std::string type = array ? declared.substr(0, declared.size() - 2) : declared;
    if (!array) {
      element(type, v);
      return v;
    }
    expect("[");
    if (accept("]")) return v;
    do element(type, v);
    while (accept(","));
    expect("]");
    return v;
  }

  // A metadata value as text: a string (unquoted), a number, or a name.
  std::string scalar_text() {
    const Token& t = peek();
    if (t.kind == Token::string || t.kind == Token::number || t.kind == Token::word) {
      ++pos_;
      return t.text;
    }
    fail("a metadata value");
  }

  std::map<std::string, std::string> metadata() {
    std::map<std::string, std::string> m;
    if (!accept("(")) return m;
    while (!accept(")")) {
      const std::string key = expect_word();
      expect("=");
      m[key] = scalar_text();
    }
    return m;
  }

  Prim prim(const std::string& parent) {
    if (expect_word() != "def") fail("'def'");
    Prim p;
    if (peek().kind == Token::word) p.type = expect_word();
    p.name = expect_kind(Token::string);
    p.path = parent + "/" + p.name;
    p.metadata = metadata();
    expect("{");
    while (!accept("}")) {
      if (peek().kind == Token::word && peek().text == "def") {
        p.children.push_back(prim(p.path));
        continue;
      }
      property(p);
    }
    return p;
  }

  void property(Prim& p) {
    std::string word = expect_word();
    if (word == "rel") {
      const std::string name = expect_word();
      expect("=");
      std::vector<std::string>& targets = p.relationships[name];
      if (accept("[")) {
        do targets.push_back(expect_kind(Token::path));
        while (accept(","));
        expect("]");
      } else {
        targets.push_back(expect_kind(Token::path));
      }
      return;
    }
    bool custom = false, uniform = false;
    if (word == "custom") { custom = true; word = expect_word(); }
    if (word == "uniform") { uniform = true; word = expect_word(); }
    std::string type = word;
    if (accept("[")) {
      expect("]");
      type += "[]";
    }
    if (!value_types.count(type.substr(0, type.find('['))))  fail("a value type");
    std::string name = expect_word();
    const bool samples = name.size() > 12 && name.compare(name.size() - 12, 12, ".timeSamples") == 0;
    if (samples) name.resize(name.size() - 12);
    Attribute& a = p.attributes[name];
    if (!a.type.empty() && a.type != type) fail("the type '" + a.type + "' of the earlier declaration of " + name);
    a.type = type;
    a.custom = a.custom || custom;
    a.uniform = a.uniform || uniform;
    if (samples) {
      if (!a.samples.empty()) fail("one timeSamples block for " + name);
      expect("=");
      expect("{");
      double previous = -1e300;
      while (!accept("}")) {
        const double code = number(Storage::twice);
        if (!(code > previous)) fail("time codes in increasing order");
        previous = code;
        expect(":");
        a.samples[code] = value(type);
        if (!accept(",")) {
          expect("}");
          break;
        }
      }
      return;
    }
    if (accept("=")) {
      if (a.value) fail("one default value for " + name);
      a.value = value(type);
    }
    for (const auto& [k, v] : metadata()) a.metadata[k] = v;
  }

  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
};

const Prim* find_in(const std::vector<Prim>& prims, const std::string& path) {
  for (const Prim& p : prims) {
    if (p.path == path) return &p;
    if (path.rfind(p.path + "/", 0) == 0) return find_in(p.children, path);
  }
  return nullptr;
}

}  // namespace

const Prim* Prim::find(const std::string& target) const { return find_in(children, target); }
const Prim* Layer::find(const std::string& target) const { return find_in(prims, target); }

Layer read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SyntaxError(path.string() + ": cannot be opened");
  std::stringstream text;
  text << in.rdbuf();
  return Parser(tokenize(text.str())).layer();
}

double to_half(double v) { return static_cast<double>(static_cast<_Float16>(v)); }

}  // namespace throng::test::usda
