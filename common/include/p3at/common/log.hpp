#pragma once
/// Grep-able log lines on stderr: `HH:MM:SS.mmm LEVEL [component] message`.
/// Messages carry key=value pairs so `grep 'event=link-lost'` finds them.
/// Thread-safe at line granularity (one fprintf per line).

#include <chrono>
#include <cstdio>
#include <ctime>
#include <string>
#include <string_view>

namespace p3at::log {

enum class Level { debug = 0, info = 1, warn = 2, error = 3, off = 4 };

/// The process-wide threshold; lines below it are dropped. Default: info.
inline Level& threshold() {
  static Level level = Level::info;
  return level;
}

inline const char* level_name(Level level) {
  switch (level) {
    case Level::debug: return "DEBUG";
    case Level::info: return "INFO ";
    case Level::warn: return "WARN ";
    case Level::error: return "ERROR";
    case Level::off: return "OFF  ";
  }
  return "?";
}

/// Writes one line if `level` passes the threshold.
inline void write(Level level, std::string_view component, std::string_view message) {
  if (level < threshold()) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  std::fprintf(stderr, "%02d:%02d:%02d.%03lld %s [%.*s] %.*s\n", utc.tm_hour, utc.tm_min, utc.tm_sec,
               static_cast<long long>(millis), level_name(level), static_cast<int>(component.size()),
               component.data(), static_cast<int>(message.size()), message.data());
}

inline void debug(std::string_view component, std::string_view message) { write(Level::debug, component, message); }
inline void info(std::string_view component, std::string_view message) { write(Level::info, component, message); }
inline void warn(std::string_view component, std::string_view message) { write(Level::warn, component, message); }
inline void error(std::string_view component, std::string_view message) { write(Level::error, component, message); }

}  // namespace p3at::log
