// The mesh helpers declared in scene_writer.h.
#include "scene_writer.h"

namespace shaderlab::scenegen {

// Makes every triangle wind counter-clockwise seen from the side its vertex normals point to,
// which is what back-face culling in the labs expects. Building each surface with the right
// winding by hand is easy to get wrong per parameterization; checking it here is not.
void orientTriangles(Geometry* g) {
    for (std::size_t t = 0; t + 2 < g->indices.size(); t += 3) {
        const Vertex& a = g->vertices[g->indices[t]];
        const Vertex& b = g->vertices[g->indices[t + 1]];
        const Vertex& c = g->vertices[g->indices[t + 2]];
        const glm::dvec3 face = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(face, a.normal + b.normal + c.normal) < 0.0)
            std::swap(g->indices[t + 1], g->indices[t + 2]);
    }
}

// Two triangles per cell of a (rows + 1) x (cols + 1) vertex grid stored row by row, then wound
// counter-clockwise. A UV sphere's first and last rows collapse to the poles, so there one
// triangle of each cell would be degenerate and is left out.
void addGridTriangles(Geometry* g, int rows, int cols, bool skip_pole_triangles) {
    const auto at = [cols](int i, int j) { return static_cast<std::uint32_t>(i * (cols + 1) + j); };
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            if (!skip_pole_triangles || i != rows - 1)
                g->indices.insert(g->indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            if (!skip_pole_triangles || i != 0)
                g->indices.insert(g->indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    orientTriangles(g);
}

// UV sphere, +Y up, seam at -Z; the poles get one triangle per segment, not a degenerate pair.
Geometry uvSphere(double radius, int segments, int rings) {
    Geometry g;
    for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            const glm::dvec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                               std::sin(theta) * std::cos(phi));
            g.vertices.push_back({radius * n, n, glm::dvec2(double(j) / segments, double(i) / rings)});
        }
    }
    addGridTriangles(&g, rings, segments, true);
    return g;
}

void computeTangents(Geometry* g) {
    const std::size_t n = g->vertices.size();
    std::vector<glm::dvec3> d_ds(n, glm::dvec3(0.0)), d_dt(n, glm::dvec3(0.0));
    std::vector<bool> used(n, false);
    for (std::size_t k = 0; k + 2 < g->indices.size(); k += 3) {
        const std::uint32_t i[3] = {g->indices[k], g->indices[k + 1], g->indices[k + 2]};
        const Vertex& a = g->vertices[i[0]];
        const Vertex& b = g->vertices[i[1]];
        const Vertex& c = g->vertices[i[2]];
        const glm::dvec3 e1 = b.position - a.position, e2 = c.position - a.position;
        // (s, t) = (u, 1 - v): the differences in t are those in v, negated.
        const double s1 = b.uv.x - a.uv.x, s2 = c.uv.x - a.uv.x;
        const double t1 = a.uv.y - b.uv.y, t2 = a.uv.y - c.uv.y;
        const double det = s1 * t2 - s2 * t1;
        if (std::abs(det) < 1e-20) continue;  // no area in texture space: no direction to learn
        const glm::dvec3 sdir = (t2 * e1 - t1 * e2) / det;
        const glm::dvec3 tdir = (s1 * e2 - s2 * e1) / det;
        for (std::uint32_t v : i) {
            used[v] = true;
            d_ds[v] += sdir;
            d_dt[v] += tdir;
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        Vertex& vert = g->vertices[v];
        const glm::dvec3 nrm = glm::normalize(vert.normal);
        if (!used[v]) {  // drawn by no triangle (a UV sphere's last pole vertex): any unit tangent
            const glm::dvec3 other = std::abs(nrm.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
            vert.tangent = glm::dvec4(glm::normalize(glm::cross(other, nrm)), 1.0);
            continue;
        }
        glm::dvec3 t = d_ds[v] - nrm * glm::dot(nrm, d_ds[v]);
        const double len = glm::length(t);
        if (!(len > 1e-12)) {
            std::fprintf(stderr, "shaderlab_make_scenes: vertex %zu has no tangent direction\n", v);
            std::exit(1);
        }
        t /= len;
        const double w = glm::dot(glm::cross(nrm, t), d_dt[v]) < 0.0 ? -1.0 : 1.0;
        vert.tangent = glm::dvec4(t, w);
    }
}

}  // namespace shaderlab::scenegen
