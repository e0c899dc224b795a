// libFuzzer target for the PARS readers: any input either parses or throws
// ParseError / CriterionError with a message (never anything else, never a
// crash), and whatever parses prints to text that parses back equal. The
// same bytes are tried as a program, as a term and as a criterion file.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "p3at/verifier/criteria.hpp"
#include "p3at/verifier/pars/parser.hpp"
#include "p3at/verifier/pars/printer.hpp"

namespace pars = p3at::verifier::pars;

namespace {

template <class Parse>
bool parses(Parse&& parse) {
  try {
    parse();
    return true;
  } catch (const pars::ParseError& e) {
    if (e.detail().empty()) std::abort();  // every rejection says what was wrong
  } catch (const p3at::verifier::CriterionError& e) {
    if (e.detail().empty()) std::abort();
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);  // bytes as text

  pars::Program program;
  if (parses([&] { program = pars::parse_program(text, "fuzz.pars"); })) {
    pars::Program again;
    if (!parses([&] { again = pars::parse_program(pars::to_string(program), "printed.pars"); }) || !(again == program)) {
      std::abort();
    }
  }

  pars::Term term;
  if (parses([&] { term = pars::parse_term(text, "fuzz.pars"); })) {
    pars::Term again;
    if (!parses([&] { again = pars::parse_term(pars::to_string(term), "printed.pars"); }) || !(again == term)) std::abort();
    if (!parses([&] { again = pars::parse_term(pars::to_pretty_string(term, 4, 60), "pretty.pars"); }) ||
        !(again == term)) {
      std::abort();
    }
  }

  p3at::verifier::Criterion criterion;
  if (parses([&] { criterion = p3at::verifier::parse_criterion(text, "fuzz.crit"); })) {
    p3at::verifier::Criterion again;
    if (!parses([&] { again = p3at::verifier::parse_criterion(p3at::verifier::to_string(criterion), "printed.crit"); }) ||
        !(again == criterion)) {
      std::abort();
    }
  }
  return 0;
}
