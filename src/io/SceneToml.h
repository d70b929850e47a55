#pragma once
// Private to src/io: the TOML vocabulary shared by the `map` file and
// `--scene` files (DESIGN sec. 4 and 5). Every accessor reports a missing or
// wrong-typed key as Error(subject, "line N: ..."), N being the line of the
// offending value (or of its table when the key is absent), so a user can find
// the mistake. Objects and lines are read in the same way from both files.
#include "core/DataSet.h"

#include <toml++/toml.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace overflight::toml_io {

// Parses TOML text; a syntax error becomes Error(subject, "line N: ...").
toml::table parse(std::string_view text, const std::string& subject);

// Rejects keys not in `allowed` (a misspelt key would otherwise be silently ignored).
void check_keys(const toml::table& table, std::initializer_list<std::string_view> allowed, const std::string& subject,
                const std::string& where);

// A number (integer or float) at `key`: required when `fallback` is null.
double number(const toml::table& table, std::string_view key, const std::string& subject, const double* fallback);
double required_number(const toml::table& table, std::string_view key, const std::string& subject);
double optional_number(const toml::table& table, std::string_view key, double fallback, const std::string& subject);
// optional_number for a value stored as float: an error when it does not fit in a float.
float optional_float(const toml::table& table, std::string_view key, float fallback, const std::string& subject);

// An array of exactly three numbers, e.g. sun_dir = [x, y, z], or the fallback when absent.
glm::vec3 optional_vec3(const toml::table& table, std::string_view key, glm::vec3 fallback, const std::string& subject);

// Appends the [[object]] and [[line]] arrays of `root` to `scene`. Model files
// are resolved against `base_dir` (the folder of the file being read).
void read_objects(const toml::table& root, const std::string& subject, const std::string& base_dir, Scene& scene);

// The inverse of read_objects: adds [[object]] and [[line]] arrays to `root`.
void write_objects(const Scene& scene, toml::table& root);

} // namespace overflight::toml_io
