#pragma once
// The PARS tokenizer and recursive-descent parser, shared by the public
// parse_* functions and by the criterion-file reader (src/criteria/), which
// parses its network and constraints with the same tokens and positions.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "p3at/verifier/pars/expr.hpp"
#include "p3at/verifier/pars/term.hpp"

namespace p3at::verifier::pars::detail {

enum class Tok {
  end, name, number,
  less, greater, less_equal, greater_equal, equal, not_equal,
  lparen, rparen, comma, semicolon, bar, hash, plus, minus, star, slash, arrow,
};

struct Token {
  Tok kind = Tok::end;
  std::string_view text;
  double number = 0.0;
  int line = 1;
  int column = 1;
  bool first_on_line = false;   ///< no token before it on its line
};

/// A '#' comment line: the text after '#' and one optional space.
struct Comment {
  int line = 0;
  std::string text;
};

/// A process term with the position of its name, for messages about it.
struct LocatedProcess {
  const Token* at = nullptr;
  std::string name;
};

class Parser {
 public:
  /// Tokenizes all of `text` (throws ParseError on a bad character or number).
  Parser(std::string_view text, std::string source);

  const Token& peek(std::size_t ahead = 0) const;
  const Token& next();
  bool at(Tok kind) const { return peek().kind == kind; }
  bool accept(Tok kind);
  const Token& expect(Tok kind, const std::string& what);
  [[noreturn]] void fail(const Token& at, const std::string& detail) const;
  /// "'x'" for a token, "the end of the input" at the end.
  static std::string describe(const Token& token);

  Term term();
  Expr expr();          ///< no comparison at the top
  Expr comparison();    ///< expr [CMP expr]
  Definition definition();
  Program program();
  void expect_end(const std::string& after);

  const std::vector<Comment>& comments() const { return comments_; }
  /// Every process parsed so far, in order (for callers that check them).
  const std::vector<LocatedProcess>& processes() const { return processes_; }
  const std::string& source() const { return source_; }
  /// Where each parameter of the process parsed last began.
  const std::vector<const Token*>& param_tokens() const { return param_tokens_; }

 private:
  struct Node {
    Expr expr;
    int depth = 1;
  };
  Term term_at(Op loosest, int nesting);
  Term primary(int nesting);
  Term process_term();
  std::vector<std::string> name_list(const std::string& what);
  Node comparison_node(int nesting);
  Node sum(int nesting);
  Node product(int nesting);
  Node unary(int nesting);
  Node atom(int nesting);
  void check_depth(int depth, const Token& at) const;
  void close_params();

  std::string source_;
  std::vector<Token> tokens_;
  std::vector<Comment> comments_;
  std::vector<LocatedProcess> processes_;
  std::vector<const Token*> param_tokens_;   ///< where each parameter of the last process began
  std::size_t pos_ = 0;
};

/// The comparison a token stands for (<, <=, >, >=, ==, !=); false for any
/// other token. Shared by expressions and criterion files.
bool compare_op(Tok kind, CompareOp& op);

}  // namespace p3at::verifier::pars::detail
