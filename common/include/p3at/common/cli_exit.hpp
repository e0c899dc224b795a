#pragma once
/// Every binary's command line: a bad flag, a missing or malformed argument
/// is "bad input", exit 2, as documented (README, docs/*.md), never CLI11's
/// own codes (105, 106, 109, 114…). Help and version still exit 0.
/// Use in main(), after #include <CLI/CLI.hpp>, in place of CLI11_PARSE.

#define P3AT_CLI_PARSE(app, argc, argv)                     \
  do {                                                      \
    try {                                                   \
      (app).parse((argc), (argv));                          \
    } catch (const CLI::ParseError& cli_error_) {           \
      return (app).exit(cli_error_) == 0 ? 0 : 2;           \
    }                                                       \
  } while (false)
