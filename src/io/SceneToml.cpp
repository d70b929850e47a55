// Based on: DESIGN sec. 5 (objects: box, house, vehicle, tower, model, and
// transmission lines), the objects of Szenberg et al. 1997 (Szenberg et al. 1997, sec. 6:
// houses, vehicles, transmission lines) and the hovercraft `map` file (CMSC 23700 project 2a, sec. 6.1).
#include "io/SceneToml.h"

#include "core/Error.h"

#include <filesystem>
#include <sstream>

namespace overflight::toml_io {

namespace {

std::string at_line(const toml::node& node) {
    const auto line = node.source().begin.line;
    return line > 0 ? "line " + std::to_string(line) + ": " : std::string();
}

std::string at_line(const toml::table& table, std::string_view key) {
    if (const toml::node* n = table.get(key)) return at_line(*n);
    return at_line(table);
}

Rgb8 color_value(const toml::table& table, std::string_view key, Rgb8 fallback, const std::string& subject,
                 const std::string& where) {
    const toml::node* n = table.get(key);
    if (!n) return fallback;
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3)
        throw Error(subject, at_line(*n) + where + std::string(key) + " must be [r, g, b] with integers 0..255");
    std::uint8_t c[3];
    for (std::size_t i = 0; i < 3; ++i) {
        // The type first: toml++'s value<int64_t>() converts a float such as
        // 3e40 to an integer without a range check, which is undefined.
        const toml::value<std::int64_t>* v = (*a)[i].as_integer();
        if (!v || v->get() < 0 || v->get() > 255)
            throw Error(subject, at_line(*n) + where + std::string(key) + " must be [r, g, b] with integers 0..255");
        c[i] = std::uint8_t(v->get());
    }
    return Rgb8{c[0], c[1], c[2]};
}

const toml::array* table_array(const toml::table& root, std::string_view key, const std::string& subject) {
    const toml::node* n = root.get(key);
    if (!n) return nullptr;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables())
        throw Error(subject, at_line(*n) + std::string(key) + " must be written as [[" + std::string(key) + "]] tables");
    return a;
}

ObjectKind object_kind(const toml::table& t, const std::string& subject) {
    const toml::node* n = t.get("kind");
    if (!n) throw Error(subject, at_line(t) + "object without kind (box, house, vehicle, tower or model)");
    const auto s = n->value<std::string>();
    if (!n->is_string()) throw Error(subject, at_line(*n) + "object kind must be a string");
    if (*s == "box") return ObjectKind::Box;
    if (*s == "house") return ObjectKind::House;
    if (*s == "vehicle") return ObjectKind::Vehicle;
    if (*s == "tower") return ObjectKind::Tower;
    if (*s == "model") return ObjectKind::Model;
    throw Error(subject, at_line(*n) + "unknown object kind '" + *s + "' (box, house, vehicle, tower or model)");
}

template <typename T>
toml::array array_of(std::initializer_list<T> values) {
    toml::array a;
    for (const T& v : values) a.push_back(v);
    return a;
}

} // namespace

toml::table parse(std::string_view text, const std::string& subject) {
    try {
        return toml::parse(text, std::string_view(subject));
    } catch (const toml::parse_error& e) {
        throw Error(subject, "line " + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
    }
}

void check_keys(const toml::table& table, std::initializer_list<std::string_view> allowed, const std::string& subject,
                const std::string& where) {
    for (const auto& [key, node] : table) {
        bool known = false;
        for (std::string_view a : allowed) known = known || key.str() == a;
        if (!known) throw Error(subject, at_line(node) + "unknown key '" + std::string(key.str()) + "'" + where);
    }
}

double number(const toml::table& table, std::string_view key, const std::string& subject, const double* fallback) {
    const toml::node* n = table.get(key);
    if (!n) {
        if (fallback) return *fallback;
        throw Error(subject, at_line(table) + "missing key " + std::string(key));
    }
    if (!n->is_number()) throw Error(subject, at_line(*n) + std::string(key) + " must be a number");
    const double v = *n->value<double>();
    if (!std::isfinite(v)) throw Error(subject, at_line(*n) + std::string(key) + " must be a finite number");
    return v;
}

double required_number(const toml::table& table, std::string_view key, const std::string& subject) {
    return number(table, key, subject, nullptr);
}

double optional_number(const toml::table& table, std::string_view key, double fallback, const std::string& subject) {
    return number(table, key, subject, &fallback);
}

float optional_float(const toml::table& table, std::string_view key, float fallback, const std::string& subject) {
    const double v = optional_number(table, key, fallback, subject);
    if (!std::isfinite(float(v))) throw Error(subject, at_line(table, key) + std::string(key) + " is beyond float range");
    return float(v);
}

glm::vec3 optional_vec3(const toml::table& table, std::string_view key, glm::vec3 fallback, const std::string& subject) {
    const toml::node* n = table.get(key);
    if (!n) return fallback;
    const toml::array* a = n->as_array();
    bool ok = a && a->size() == 3;
    // Stored as float: a double beyond float range would become inf and not survive format_map/parse_map.
    for (std::size_t i = 0; ok && i < 3; ++i)
        ok = (*a)[i].is_number() && std::isfinite(float(*(*a)[i].value<double>()));
    if (!ok) throw Error(subject, at_line(*n) + std::string(key) + " must be an array of three numbers within float range");
    return {float(*(*a)[0].value<double>()), float(*(*a)[1].value<double>()), float(*(*a)[2].value<double>())};
}

void read_objects(const toml::table& root, const std::string& subject, const std::string& base_dir, Scene& scene) {
    if (const toml::array* objects = table_array(root, "object", subject)) {
        for (const toml::node& node : *objects) {
            const toml::table& t = *node.as_table();
            check_keys(t, {"kind", "x", "y", "z", "width", "height", "depth", "heading", "scale", "color", "file"},
                       subject, " in [[object]]");
            SceneObject o;
            o.kind = object_kind(t, subject);
            o.x = required_number(t, "x", subject);
            o.z = required_number(t, "z", subject);
            if (t.contains("y")) o.y = required_number(t, "y", subject);
            o.width = optional_number(t, "width", o.width, subject);
            o.height = optional_number(t, "height", o.height, subject);
            o.depth = optional_number(t, "depth", o.depth, subject);
            if (!(o.width > 0 && o.height > 0 && o.depth > 0))
                throw Error(subject, at_line(t) + "object width, height and depth must be positive");
            o.heading = optional_number(t, "heading", o.heading, subject);
            o.scale = optional_number(t, "scale", o.scale, subject);
            if (!(o.scale > 0)) throw Error(subject, at_line(t, "scale") + "scale must be positive");
            o.color = color_value(t, "color", o.color, subject, "");
            if (o.kind == ObjectKind::Model) {
                const toml::node* f = t.get("file");
                if (!f) throw Error(subject, at_line(t) + "model object without file (an OBJ or glTF path)");
                if (!f->is_string()) throw Error(subject, at_line(*f) + "file must be a string");
                std::filesystem::path p(*f->value<std::string>());
                // Relative to the scene file, so a scene folder can be moved as a whole.
                if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
                o.model_path = p.lexically_normal().string();
            } else if (t.contains("file")) {
                throw Error(subject, at_line(t, "file") + "file is only meaningful for kind = \"model\"");
            }
            scene.objects.push_back(o);
        }
    }
    if (const toml::array* lines = table_array(root, "line", subject)) {
        for (const toml::node& node : *lines) {
            const toml::table& t = *node.as_table();
            check_keys(t, {"points", "height", "sag", "color"}, subject, " in [[line]]");
            TransmissionLine line;
            const toml::node* pn = t.get("points");
            if (!pn) throw Error(subject, at_line(t) + "line without points = [[x, z], ...]");
            const toml::array* pts = pn->as_array();
            if (!pts || pts->size() < 2)
                throw Error(subject, at_line(*pn) + "points must be an array of at least two [x, z] pairs");
            for (const toml::node& p : *pts) {
                const toml::array* xz = p.as_array();
                if (!xz || xz->size() != 2 || !(*xz)[0].is_number() || !(*xz)[1].is_number())
                    throw Error(subject, at_line(*pn) + "each point must be [x, z] with two numbers");
                const double x = *(*xz)[0].value<double>(), z = *(*xz)[1].value<double>();
                if (!std::isfinite(x) || !std::isfinite(z)) throw Error(subject, at_line(*pn) + "point is not finite");
                line.points.emplace_back(x, z);
            }
            line.height = optional_number(t, "height", line.height, subject);
            line.sag = optional_number(t, "sag", line.sag, subject);
            if (!(line.height > 0) || line.sag < 0)
                throw Error(subject, at_line(t) + "line height must be positive and sag not negative");
            line.color = color_value(t, "color", line.color, subject, "");
            scene.lines.push_back(std::move(line));
        }
    }
}

void write_objects(const Scene& scene, toml::table& root) {
    toml::array objects;
    for (const SceneObject& o : scene.objects) {
        toml::table t{{"kind", to_string(o.kind)}, {"x", o.x}, {"z", o.z}, {"width", o.width}, {"height", o.height},
                      {"depth", o.depth}, {"heading", o.heading}};
        if (o.y) t.insert("y", *o.y);
        if (o.kind == ObjectKind::Model) {
            t.insert("scale", o.scale);
            t.insert("file", o.model_path);
        }
        t.insert("color", array_of<std::int64_t>({o.color.r, o.color.g, o.color.b}));
        objects.push_back(std::move(t));
    }
    if (!objects.empty()) root.insert("object", std::move(objects));
    toml::array lines;
    for (const TransmissionLine& l : scene.lines) {
        toml::array pts;
        for (const glm::dvec2& p : l.points) pts.push_back(array_of<double>({p.x, p.y}));
        lines.push_back(toml::table{{"points", std::move(pts)}, {"height", l.height}, {"sag", l.sag},
                                    {"color", array_of<std::int64_t>({l.color.r, l.color.g, l.color.b})}});
    }
    if (!lines.empty()) root.insert("line", std::move(lines));
}

} // namespace overflight::toml_io
