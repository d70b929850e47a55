// Based on: Szenberg et al. 1997 sec. 5 (polygonal objects); formats through
// tinyobjloader (Wavefront OBJ) and tinygltf (Khronos glTF 2.0).
#include "io/ModelLoader.h"

#include "core/Error.h"

#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

namespace overflight {

namespace {

std::uint8_t to_byte(double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

// Flat normal of a triangle (unit; +Y for degenerate ones).
glm::vec3 face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    return len > 0 ? n / len : glm::vec3(0, 1, 0);
}

void check_finite(const std::string& path, const glm::vec3& p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw Error(path, "vertex coordinate is not a finite number");
}

MeshArrays load_obj(const std::string& path, Rgb8 fallback) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = std::filesystem::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string msg = reader.Error();
        std::replace(msg.begin(), msg.end(), '\n', ' ');
        while (!msg.empty() && msg.back() == ' ') msg.pop_back();
        throw Error(path, "malformed OBJ" + (msg.empty() ? std::string() : ": " + msg));
    }
    const auto& attrib = reader.GetAttrib();
    const auto& materials = reader.GetMaterials();
    const std::size_t n_pos = attrib.vertices.size() / 3, n_nrm = attrib.normals.size() / 3;
    MeshArrays mesh;
    // Every face corner becomes its own vertex: OBJ indexes positions and
    // normals separately, and flat faces need their own normals anyway.
    for (const auto& shape : reader.GetShapes()) {
        const auto& m = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            const int fv = m.num_face_vertices[f];
            if (fv != 3) throw Error(path, "malformed OBJ: face with " + std::to_string(fv) + " corners");
            Rgb8 color = fallback;
            const int mat = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (mat >= 0 && std::size_t(mat) < materials.size())
                color = {to_byte(materials[std::size_t(mat)].diffuse[0]), to_byte(materials[std::size_t(mat)].diffuse[1]),
                         to_byte(materials[std::size_t(mat)].diffuse[2])};
            glm::vec3 p[3], n[3];
            bool has_normals = true;
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t idx = m.indices[offset + std::size_t(k)];
                if (idx.vertex_index < 0 || std::size_t(idx.vertex_index) >= n_pos)
                    throw Error(path, "malformed OBJ: face refers to a missing vertex");
                const float* v = &attrib.vertices[3 * std::size_t(idx.vertex_index)];
                p[k] = {v[0], v[1], v[2]};
                check_finite(path, p[k]);
                if (idx.normal_index >= 0 && std::size_t(idx.normal_index) < n_nrm) {
                    const float* vn = &attrib.normals[3 * std::size_t(idx.normal_index)];
                    n[k] = glm::vec3(vn[0], vn[1], vn[2]);
                    if (!(glm::length(n[k]) > 0)) has_normals = false;
                } else {
                    has_normals = false;
                }
            }
            const glm::vec3 flat = face_normal(p[0], p[1], p[2]);
            for (int k = 0; k < 3; ++k) {
                mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
                mesh.positions.push_back(p[k]);
                mesh.normals.push_back(has_normals ? glm::normalize(n[k]) : flat);
                mesh.colors.push_back(color);
            }
            offset += 3;
        }
    }
    return mesh;
}

// Reads accessor `index` as `comps` floats per element (VEC3 float only for
// positions/normals; scalar unsigned integers for indices).
template <typename Fn>
void for_each_element(const std::string& path, const tinygltf::Model& model, int index, Fn&& fn) {
    if (index < 0 || std::size_t(index) >= model.accessors.size()) throw Error(path, "malformed glTF: bad accessor");
    const tinygltf::Accessor& acc = model.accessors[std::size_t(index)];
    if (acc.bufferView < 0 || std::size_t(acc.bufferView) >= model.bufferViews.size())
        throw Error(path, "malformed glTF: accessor without buffer view");
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(acc.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size())
        throw Error(path, "malformed glTF: buffer view without buffer");
    const auto& data = model.buffers[std::size_t(view.buffer)].data;
    const int elem_size = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType)) *
                          tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
    if (elem_size <= 0) throw Error(path, "malformed glTF: unknown accessor type");
    const std::size_t stride = view.byteStride ? view.byteStride : std::size_t(elem_size);
    const std::size_t start = view.byteOffset + acc.byteOffset;
    if (acc.count > 0 && start + stride * (acc.count - 1) + std::size_t(elem_size) > data.size())
        throw Error(path, "malformed glTF: accessor runs past the end of its buffer");
    for (std::size_t i = 0; i < acc.count; ++i) fn(acc, data.data() + start + stride * i);
}

MeshArrays load_gltf(const std::string& path, bool binary, Rgb8 fallback) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok) {
        std::replace(err.begin(), err.end(), '\n', ' ');
        while (!err.empty() && err.back() == ' ') err.pop_back();
        throw Error(path, "malformed glTF" + (err.empty() ? std::string() : ": " + err));
    }
    MeshArrays mesh;
    auto add_mesh = [&](const tinygltf::Mesh& gm, const glm::mat4& xf) {
        const glm::mat3 nxf = glm::transpose(glm::inverse(glm::mat3(xf)));
        for (const auto& prim : gm.primitives) {
            if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue; // lines/points/strips: not solids
            const auto pos_it = prim.attributes.find("POSITION");
            if (pos_it == prim.attributes.end()) throw Error(path, "malformed glTF: primitive without POSITION");
            std::vector<glm::vec3> pos, nrm;
            for_each_element(path, model, pos_it->second, [&](const tinygltf::Accessor& a, const unsigned char* p) {
                if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != TINYGLTF_TYPE_VEC3)
                    throw Error(path, "malformed glTF: POSITION is not float VEC3");
                glm::vec3 v;
                std::memcpy(&v, p, sizeof v);
                pos.push_back(glm::vec3(xf * glm::vec4(v, 1.0f)));
                check_finite(path, pos.back());
            });
            if (const auto n_it = prim.attributes.find("NORMAL"); n_it != prim.attributes.end())
                for_each_element(path, model, n_it->second, [&](const tinygltf::Accessor& a, const unsigned char* p) {
                    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != TINYGLTF_TYPE_VEC3)
                        throw Error(path, "malformed glTF: NORMAL is not float VEC3");
                    glm::vec3 v;
                    std::memcpy(&v, p, sizeof v);
                    nrm.push_back(nxf * v);
                });
            std::vector<std::uint32_t> idx;
            if (prim.indices >= 0) {
                for_each_element(path, model, prim.indices, [&](const tinygltf::Accessor& a, const unsigned char* p) {
                    switch (a.componentType) {
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: idx.push_back(*p); break;
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t v; std::memcpy(&v, p, 2); idx.push_back(v); break; }
                    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t v; std::memcpy(&v, p, 4); idx.push_back(v); break; }
                    default: throw Error(path, "malformed glTF: indices are not unsigned integers");
                    }
                });
            } else {
                for (std::uint32_t i = 0; i < pos.size(); ++i) idx.push_back(i);
            }
            if (idx.size() % 3 != 0) throw Error(path, "malformed glTF: triangle list length is not a multiple of 3");
            Rgb8 color = fallback;
            if (prim.material >= 0 && std::size_t(prim.material) < model.materials.size()) {
                const auto& f = model.materials[std::size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
                if (f.size() >= 3) color = {to_byte(f[0]), to_byte(f[1]), to_byte(f[2])};
            }
            const bool has_normals = nrm.size() == pos.size();
            for (std::size_t t = 0; t < idx.size(); t += 3) {
                for (int k = 0; k < 3; ++k)
                    if (idx[t + std::size_t(k)] >= pos.size()) throw Error(path, "malformed glTF: index out of range");
                const glm::vec3 flat = face_normal(pos[idx[t]], pos[idx[t + 1]], pos[idx[t + 2]]);
                for (int k = 0; k < 3; ++k) {
                    const std::uint32_t i = idx[t + std::size_t(k)];
                    mesh.indices.push_back(std::uint32_t(mesh.positions.size()));
                    mesh.positions.push_back(pos[i]);
                    const bool good = has_normals && glm::length(nrm[i]) > 0;
                    mesh.normals.push_back(good ? glm::normalize(nrm[i]) : flat);
                    mesh.colors.push_back(color);
                }
            }
        }
    };
    // Walk the node hierarchy of the default scene (or every root) with the
    // accumulated transforms (glTF 2.0 sec. 3.5.2: matrix, or T * R * S).
    std::function<void(int, const glm::mat4&, int)> visit = [&](int node_index, const glm::mat4& parent, int depth) {
        if (node_index < 0 || std::size_t(node_index) >= model.nodes.size() || depth > 64)
            throw Error(path, "malformed glTF: bad node hierarchy");
        const tinygltf::Node& node = model.nodes[std::size_t(node_index)];
        glm::mat4 local(1.0f);
        if (node.matrix.size() == 16) {
            for (int i = 0; i < 16; ++i) local[i / 4][i % 4] = float(node.matrix[std::size_t(i)]);
        } else {
            if (node.translation.size() == 3)
                local = glm::translate(local, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
            if (node.rotation.size() == 4)
                local *= glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]),
                                                  float(node.rotation[1]), float(node.rotation[2])));
            if (node.scale.size() == 3)
                local = glm::scale(local, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
        }
        const glm::mat4 xf = parent * local;
        if (node.mesh >= 0) {
            if (std::size_t(node.mesh) >= model.meshes.size()) throw Error(path, "malformed glTF: bad mesh index");
            add_mesh(model.meshes[std::size_t(node.mesh)], xf);
        }
        for (int child : node.children) visit(child, xf, depth + 1);
    };
    if (!model.scenes.empty()) {
        const int s = model.defaultScene >= 0 && std::size_t(model.defaultScene) < model.scenes.size() ? model.defaultScene : 0;
        for (int root : model.scenes[std::size_t(s)].nodes) visit(root, glm::mat4(1.0f), 0);
    } else {
        for (const auto& gm : model.meshes) add_mesh(gm, glm::mat4(1.0f));
    }
    return mesh;
}

} // namespace

MeshArrays load_model(const std::string& path, Rgb8 fallback) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(path, "model file not found");
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    MeshArrays mesh;
    if (ext == ".obj") mesh = load_obj(path, fallback);
    else if (ext == ".gltf") mesh = load_gltf(path, false, fallback);
    else if (ext == ".glb") mesh = load_gltf(path, true, fallback);
    else throw Error(path, "unknown model format '" + ext + "' (expected .obj, .gltf or .glb)");
    if (mesh.indices.empty()) throw Error(path, "model has no triangles");
    return mesh;
}

void load_scene_models(Scene& scene) {
    std::map<std::pair<std::string, std::uint32_t>, std::shared_ptr<const MeshArrays>> loaded;
    for (SceneObject& o : scene.objects) {
        if (o.kind != ObjectKind::Model || o.model) continue;
        const auto key = std::make_pair(o.model_path, std::uint32_t(o.color.r) << 16 | std::uint32_t(o.color.g) << 8 | o.color.b);
        auto& model = loaded[key];
        if (!model) model = std::make_shared<const MeshArrays>(load_model(o.model_path, o.color));
        o.model = model;
    }
}

} // namespace overflight
