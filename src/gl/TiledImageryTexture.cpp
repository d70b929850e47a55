// See TiledImageryTexture.h.
#include "gl/TiledImageryTexture.h"

#include <algorithm>
#include <climits>

namespace overflight::gl {

namespace {

bool same_layout(const ImageryTileLayout& a, const ImageryTileLayout& b) {
    return a.cols == b.cols && a.rows == b.rows && a.levels == b.levels;
}

void upload_layer(GLuint texture, int layer, const TileImagery& tile) {
    for (std::size_t m = 0; m < tile.levels.size(); ++m) {
        const Image2D<Rgba8>& img = tile.levels[m];
        glTextureSubImage3D(texture, GLint(m), 0, 0, layer, img.width, img.height, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                            img.pixels.data());
    }
}

} // namespace

void TiledImageryTexture::update(const TileImageryFrame& frame) {
    uniform_ = size_uniform_ = glm::vec4(0.0f);
    if (frame.tiles.empty() || !frame.layout.present()) return;
    const ImageryTileLayout& l = frame.layout;
    const int needed = int(frame.tiles.size());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (!array_.get() || needed > capacity_ || !same_layout(l, layout_)) {
        GLint most = 256;
        glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &most);
        capacity_ = std::min(int(most), std::max({needed, 2 * capacity_, 4}));
        layout_ = l;
        array_ = make_texture(GL_TEXTURE_2D_ARRAY);
        glTextureStorage3D(array_.get(), l.levels + 1, GL_RGBA8, l.cols, l.rows, capacity_);
        glTextureParameteri(array_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(array_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(array_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(array_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(array_.get(), GL_TEXTURE_MAX_LEVEL, l.levels);
        if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
            GLfloat aniso = 1.0f;
            glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &aniso);
            glTextureParameterf(array_.get(), GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(aniso, 16.0f));
        }
        layers_.assign(std::size_t(capacity_), nullptr);
    }
    // Layers of tiles this frame keeps stay; the others are free.
    std::vector<int> layer_of(frame.tiles.size(), -1);
    std::vector<char> kept(layers_.size(), 0);
    for (std::size_t k = 0; k < frame.tiles.size(); ++k)
        for (std::size_t i = 0; i < layers_.size(); ++i)
            if (layers_[i] == frame.tiles[k]) {
                layer_of[k] = int(i);
                kept[i] = 1;
                break;
            }
    std::size_t next_free = 0;
    int r0 = INT_MAX, c0 = INT_MAX, r1 = INT_MIN, c1 = INT_MIN;
    for (std::size_t k = 0; k < frame.tiles.size(); ++k) {
        const TileImagery& t = *frame.tiles[k];
        if (layer_of[k] < 0) {
            while (next_free < layers_.size() && kept[next_free]) ++next_free;
            if (next_free == layers_.size()) continue; // more than the GL's layers: this tile shows its samples' colors
            layers_[next_free] = frame.tiles[k];
            kept[next_free] = 1;
            layer_of[k] = int(next_free);
            upload_layer(array_.get(), layer_of[k], t);
        }
        r0 = std::min(r0, t.r);
        r1 = std::max(r1, t.r);
        c0 = std::min(c0, t.c);
        c1 = std::max(c1, t.c);
    }
    if (r0 > r1) return;
    const int cols = c1 - c0 + 1, rows = r1 - r0 + 1;
    if (!pages_.get() || cols != page_cols_ || rows != page_rows_) {
        pages_ = make_texture(GL_TEXTURE_2D);
        glTextureStorage2D(pages_.get(), 1, GL_RGBA32F, cols, rows);
        glTextureParameteri(pages_.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(pages_.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        page_cols_ = cols;
        page_rows_ = rows;
    }
    std::vector<glm::vec4> table(std::size_t(cols) * std::size_t(rows), glm::vec4(0.0f));
    for (std::size_t k = 0; k < frame.tiles.size(); ++k) {
        if (layer_of[k] < 0) continue;
        const TileImagery& t = *frame.tiles[k];
        table[std::size_t(t.r - r0) * std::size_t(cols) + std::size_t(t.c - c0)] =
            glm::vec4(float(layer_of[k] + 1), float(l.x_of(t.u0)), float(l.z_of(t.v0)), 0.0f);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(pages_.get(), 0, 0, 0, cols, rows, GL_RGBA, GL_FLOAT, table.data());
    glBindTextureUnit(kArrayUnit, array_.get());
    glBindTextureUnit(kPageUnit, pages_.get());
    uniform_ = glm::vec4(float(1.0 / frame.tile_world_size), float(l.levels), float(c0), float(r0));
    size_uniform_ = glm::vec4(float(1.0 / (l.cols * l.texel_x())), float(1.0 / (l.rows * l.texel_z())), float(l.cols),
                              float(l.rows));
}

} // namespace overflight::gl
