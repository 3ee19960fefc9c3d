#include "tools/scene/toml_limits.hpp"

#include <vector>

namespace gyrostab::tools {

namespace {

// A lexical walk of TOML that knows strings, comments, table headers, keys and values, enough to count how
// deep each statement nests; it validates nothing (the parser does, afterwards).
class NestingScanner {
 public:
  explicit NestingScanner(std::string_view t) : t_(t) {}

  int run(int stop_above, int* line_of_max) {
    while (i_ < t_.size()) {
      if (max_ > stop_above) break;  // enough to refuse: no need to walk the rest of a hostile file
      step();
    }
    if (line_of_max != nullptr) *line_of_max = max_line_;
    return max_;
  }

 private:
  enum class Mode { kLineStart, kHeader, kKey, kValue, kAfterStatement };
  struct Frame {
    bool inline_table;
    int key_depth;  // the components of the key being read inside an inline table
  };

  char peek(std::size_t k = 0) const { return i_ + k < t_.size() ? t_[i_ + k] : '\0'; }

  int depth() const {
    int d = table_depth_ + key_depth_;
    for (const Frame& f : stack_) d += 1 + f.key_depth;
    return d;
  }
  void note_depth() {
    const int d = depth();
    if (d > max_) {
      max_ = d;
      max_line_ = line_;
    }
  }

  void newline() {
    ++line_;
    ++i_;
    if (stack_.empty() && mode_ != Mode::kHeader) {
      mode_ = Mode::kLineStart;
      key_depth_ = 0;
    } else if (mode_ == Mode::kHeader) {
      mode_ = Mode::kLineStart;
    }
  }

  void skip_comment() {
    while (i_ < t_.size() && t_[i_] != '\n') ++i_;
  }

  // A string starting at i_ (quote char q); multi-line when tripled.
  void skip_string() {
    const char q = peek();
    if (peek(1) == q && peek(2) == q) {
      i_ += 3;
      while (i_ < t_.size()) {
        if (q == '"' && t_[i_] == '\\') {
          i_ += 2;
          continue;
        }
        if (t_[i_] == '\n') ++line_;
        if (t_[i_] == q && peek(1) == q && peek(2) == q) {
          i_ += 3;
          while (peek() == q) ++i_;  // up to two quotes may close the content
          return;
        }
        ++i_;
      }
      return;
    }
    ++i_;
    while (i_ < t_.size() && t_[i_] != q && t_[i_] != '\n') {
      if (q == '"' && t_[i_] == '\\') ++i_;
      ++i_;
    }
    if (peek() == q) ++i_;
  }

  void step() {
    const char c = peek();
    if (c == '\n') {
      newline();
      return;
    }
    if (c == '#') {
      skip_comment();
      return;
    }
    switch (mode_) {
      case Mode::kLineStart:
        if (c == ' ' || c == '\t' || c == '\r') {
          ++i_;
        } else if (c == '[') {
          mode_ = Mode::kHeader;
          table_depth_ = 1;
          ++i_;
          note_depth();
        } else {
          mode_ = Mode::kKey;
          key_depth_ = 1;
          note_depth();
        }
        return;
      case Mode::kHeader:
        if (c == '"' || c == '\'') {
          skip_string();
        } else if (c == '.') {
          ++table_depth_;
          ++i_;
          note_depth();
        } else if (c == ']') {
          mode_ = Mode::kAfterStatement;
          ++i_;
        } else {
          ++i_;
        }
        return;
      case Mode::kKey: {
        int& kd = stack_.empty() ? key_depth_ : stack_.back().key_depth;
        if (c == '"' || c == '\'') {
          skip_string();
        } else if (c == '.') {
          ++kd;
          ++i_;
          note_depth();
        } else if (c == '=') {
          mode_ = Mode::kValue;
          ++i_;
        } else if (c == '}' && !stack_.empty()) {  // an empty inline table
          close();
        } else {
          ++i_;
        }
        return;
      }
      case Mode::kValue:
        if (c == '"' || c == '\'') {
          skip_string();
        } else if (c == '[' || c == '{') {
          stack_.push_back(Frame{c == '{', c == '{' ? 1 : 0});
          ++i_;
          note_depth();
          if (c == '{') mode_ = Mode::kKey;
        } else if (c == ']' || c == '}') {
          close();
        } else if (c == ',' && !stack_.empty() && stack_.back().inline_table) {
          stack_.back().key_depth = 1;
          mode_ = Mode::kKey;
          ++i_;
        } else {
          ++i_;
        }
        return;
      case Mode::kAfterStatement:
        ++i_;
        return;
    }
  }

  void close() {
    ++i_;
    if (!stack_.empty()) stack_.pop_back();
    if (stack_.empty()) {
      mode_ = Mode::kAfterStatement;
    } else {
      mode_ = Mode::kValue;
      if (stack_.back().inline_table) stack_.back().key_depth = 1;
    }
  }

  std::string_view t_;
  std::size_t i_{0};
  int line_{1};
  Mode mode_{Mode::kLineStart};
  int table_depth_{0};
  int key_depth_{0};
  std::vector<Frame> stack_;
  int max_{0};
  int max_line_{0};
};

}  // namespace

int toml_nesting_depth(std::string_view text, int* line_of_max) {
  return NestingScanner(text).run(1 << 30, line_of_max);
}

std::string toml_limits_problem(std::string_view text, const std::string& name) {
  if (text.size() > kMaxSceneBytes) {
    return name + ": " + std::to_string(text.size()) + " bytes, larger than a scene may be (" +
           std::to_string(kMaxSceneBytes) + " bytes); not parsed";
  }
  int line = 0;
  const int depth = NestingScanner(text).run(kMaxTomlNesting, &line);
  if (depth > kMaxTomlNesting) {
    return name + ":" + std::to_string(line) + ": nested more than " + std::to_string(kMaxTomlNesting) +
           " levels deep (tables, dotted keys, arrays and inline tables together); not parsed";
  }
  return "";
}

}  // namespace gyrostab::tools
