#include "sweep/sqlite_database.hpp"

#include <cmath>

#include "mjarm/error.hpp"

namespace mjarm {

SqliteDatabase::SqliteDatabase(const std::filesystem::path& path, bool create) : path_(path) {
  const int flags = SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string reason = db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw Error("cannot open results database '" + path.string() + "': " + reason);
  }
}

SqliteDatabase::~SqliteDatabase() { sqlite3_close(db_); }

void SqliteDatabase::fail(const std::string& what) const {
  throw Error("results database '" + path_.string() + "': " + what + ": " + sqlite3_errmsg(db_));
}

void SqliteDatabase::execute(const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string reason = message != nullptr ? message : "unknown error";
    sqlite3_free(message);
    throw Error("results database '" + path_.string() + "': " + reason +
                " (in: " + sql.substr(0, 80) + ")");
  }
}

SqliteStatement SqliteDatabase::prepare(const std::string& sql) { return {*this, sql}; }

void SqliteDatabase::close() {
  if (db_ != nullptr && sqlite3_close(db_) != SQLITE_OK) fail("cannot close");
  db_ = nullptr;
}

SqliteStatement::SqliteStatement(SqliteDatabase& db, const std::string& sql) : db_(&db) {
  if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK)
    db.fail("cannot prepare '" + sql.substr(0, 80) + "'");
}

SqliteStatement::SqliteStatement(SqliteStatement&& other) noexcept
    : db_(other.db_), statement_(other.statement_) {
  other.statement_ = nullptr;
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

void SqliteStatement::bind(int index, const nlohmann::ordered_json& value) {
  int rc = SQLITE_OK;
  if (value.is_null()) {
    rc = sqlite3_bind_null(statement_, index);
  } else if (value.is_boolean()) {
    rc = sqlite3_bind_int64(statement_, index, value.get<bool>() ? 1 : 0);
  } else if (value.is_number_integer()) {
    rc = sqlite3_bind_int64(statement_, index, value.get<std::int64_t>());
  } else if (value.is_number()) {
    const double x = value.get<double>();
    rc = std::isfinite(x) ? sqlite3_bind_double(statement_, index, x)
                          : sqlite3_bind_null(statement_, index);
  } else {
    const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
    rc = sqlite3_bind_text(statement_, index, text.c_str(), static_cast<int>(text.size()),
                           SQLITE_TRANSIENT);
  }
  if (rc != SQLITE_OK) db_->fail("cannot bind a value");
}

bool SqliteStatement::step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc != SQLITE_DONE) db_->fail("a statement failed");
  return false;
}

void SqliteStatement::reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

int SqliteStatement::columns() const noexcept { return sqlite3_column_count(statement_); }

std::string SqliteStatement::column_name(int index) const {
  return sqlite3_column_name(statement_, index);
}

nlohmann::ordered_json SqliteStatement::column(int index) const {
  switch (sqlite3_column_type(statement_, index)) {
    case SQLITE_INTEGER:
      return static_cast<std::int64_t>(sqlite3_column_int64(statement_, index));
    case SQLITE_FLOAT:
      return sqlite3_column_double(statement_, index);
    case SQLITE_TEXT:
      return std::string(reinterpret_cast<const char*>(sqlite3_column_text(statement_, index)),
                         static_cast<std::size_t>(sqlite3_column_bytes(statement_, index)));
    default:
      return nullptr;
  }
}

std::string sql_name(const std::string& name) {
  std::string quoted = "\"";
  for (const char c : name) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace mjarm
