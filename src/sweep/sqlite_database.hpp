#pragma once
// A SQLite database (Debian's libsqlite3) as the sweep's results use it: open, run statements,
// bind and read values. Every failure throws Error with SQLite's message and the file.

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace mjarm {

class SqliteStatement;

class SqliteDatabase {
 public:
  /// Opens @p path (created when @p create).
  /// @throws Error "cannot open results database 'F': <reason>"
  SqliteDatabase(const std::filesystem::path& path, bool create);
  ~SqliteDatabase();
  SqliteDatabase(const SqliteDatabase&) = delete;
  SqliteDatabase& operator=(const SqliteDatabase&) = delete;

  /// Runs @p sql (one or more statements without results).
  void execute(const std::string& sql);
  SqliteStatement prepare(const std::string& sql);
  /// Closes the file, throwing when it fails (the destructor closes quietly).
  void close();

  [[noreturn]] void fail(const std::string& what) const;
  sqlite3* handle() const noexcept { return db_; }

 private:
  sqlite3* db_ = nullptr;
  std::filesystem::path path_;
};

class SqliteStatement {
 public:
  SqliteStatement(SqliteDatabase& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(SqliteStatement&& other) noexcept;
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;
  SqliteStatement& operator=(SqliteStatement&&) = delete;

  /// Binds parameter @p index (from 1): null, a flag or whole number (INTEGER), a number (REAL,
  /// NULL when not finite), a string (TEXT), an array or object (TEXT, its JSON).
  void bind(int index, const nlohmann::ordered_json& value);
  /// Steps once: true when a row is ready.
  bool step();
  /// Resets for the next bindings.
  void reset();

  int columns() const noexcept;
  std::string column_name(int index) const;
  /// The value of column @p index of the current row as JSON (NULL as null).
  nlohmann::ordered_json column(int index) const;

 private:
  SqliteDatabase* db_;
  sqlite3_stmt* statement_ = nullptr;
};

/// @p name quoted as an SQL identifier ("object-size" → "\"object-size\"").
std::string sql_name(const std::string& name);

}  // namespace mjarm
