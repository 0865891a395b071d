// The glTF loader's materials: images (kept encoded), textures with their samplers, and
// metallic-roughness materials with their factors and texture references. A bad factor or a
// texture reference to nothing is a warning and a default, not an error: the mesh still draws.
// What it does not: decode images (the renderer does, for the ones a program samples:
// material_textures.cpp), or read any KHR_materials_* or KHR_texture_transform extension (the
// loader warns that they are ignored).
#include <tiny_gltf.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "gltf_converter.h"

namespace shaderlab::gltf_detail {

void Converter::convertImages() {
    for (int i : images_.dropped)
        warnings_.push_back("image " + std::to_string(i) + ": the scene's images exceed " +
                            std::to_string(kMaxFileBytes >> 20) + " MiB in all; this one is not kept");
    for (std::size_t i = 0; i < model_.images.size(); ++i) {
        const tinygltf::Image& src = model_.images[i];
        TextureImage image;
        image.name = src.name.empty() ? "image" + std::to_string(i) : src.name;
        if (src.bufferView >= 0) {
            // A bad view loses this image only: the renderer binds a white texture in its place.
            try {
                const Bytes view = bufferView(src.bufferView, "image " + std::to_string(i));
                image.bytes.assign(view.data, view.data + view.size);
            } catch (const LoadError& e) {
                warnings_.push_back(e.message + "; the image is left out");
            }
        } else if (auto it = images_.by_image.find(static_cast<int>(i)); it != images_.by_image.end()) {
            image.bytes = std::move(it->second);
        }
        scene_.images.push_back(std::move(image));
    }
}

void Converter::convertTextures() {
    for (std::size_t i = 0; i < model_.textures.size(); ++i) {
        const tinygltf::Texture& src = model_.textures[i];
        Texture t;
        if (src.source >= 0 && static_cast<std::size_t>(src.source) < model_.images.size()) {
            const tinygltf::Image& image = model_.images[static_cast<std::size_t>(src.source)];
            t.image = src.source;
            t.image_uri = image.uri.rfind("data:", 0) == 0 ? std::string() : image.uri;
            t.mime_type = image.mimeType;
        }
        if (src.sampler >= 0 && static_cast<std::size_t>(src.sampler) < model_.samplers.size()) {
            const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(src.sampler)];
            t.mag_filter = sampler.magFilter;
            t.min_filter = sampler.minFilter;
            t.wrap_s = sampler.wrapS;
            t.wrap_t = sampler.wrapT;
        }
        scene_.textures.push_back(std::move(t));
    }
}

void Converter::convertMaterials() {
    convertImages();
    convertTextures();
    const auto textureRef = [&](const std::string& who, int index, int texcoord, double scale, bool srgb) {
        TextureRef ref;
        if (index < 0) return ref;
        if (static_cast<std::size_t>(index) >= scene_.textures.size()) {
            warnings_.push_back(who + ": texture " + std::to_string(index) +
                                " does not exist; slot left empty");
            return ref;
        }
        if (texcoord < 0 || texcoord > 1) {
            warnings_.push_back(who + ": reads TEXCOORD_" + std::to_string(texcoord) +
                                "; only TEXCOORD_0 and TEXCOORD_1 are passed to shaders");
        }
        ref.texture = index;
        ref.texcoord = texcoord;
        ref.scale = std::isfinite(scale) ? static_cast<float>(scale) : 1.0f;
        // Colour textures hold sRGB-encoded values, data textures linear ones (glTF 2.0, 3.9).
        if (srgb) scene_.textures[static_cast<std::size_t>(index)].srgb = true;
        return ref;
    };
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& src = model_.materials[i];
        const std::string who = "material " + std::to_string(i);
        Material m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        const auto& pbr = src.pbrMetallicRoughness;
        const auto& f = pbr.baseColorFactor;
        const glm::vec4 color = f.size() == 4 ? glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]),
                                                          static_cast<float>(f[2]), static_cast<float>(f[3]))
                                              : glm::vec4(std::numeric_limits<float>::quiet_NaN());
        if (std::isfinite(color.r + color.g + color.b + color.a)) {
            m.base_color = color;
        } else {
            warnings_.push_back(who + ": baseColorFactor is not 4 finite numbers; white used");
        }
        const auto unit = [&](double v, float fallback, const char* name) {
            if (std::isfinite(v) && v >= 0.0 && v <= 1.0) return static_cast<float>(v);
            warnings_.push_back(who + ": " + name + " must be in 0..1; " + std::to_string(fallback) +
                                " used");
            return fallback;
        };
        m.metallic = unit(pbr.metallicFactor, 1.0f, "metallicFactor");
        m.roughness = unit(pbr.roughnessFactor, 1.0f, "roughnessFactor");
        if (src.emissiveFactor.size() == 3 && finite(src.emissiveFactor)) {
            m.emissive = glm::vec3(static_cast<float>(src.emissiveFactor[0]),
                                   static_cast<float>(src.emissiveFactor[1]),
                                   static_cast<float>(src.emissiveFactor[2]));
        }
        m.double_sided = src.doubleSided;
        m.alpha_mode = src.alphaMode == "MASK"    ? AlphaMode::Mask
                       : src.alphaMode == "BLEND" ? AlphaMode::Blend
                                                  : AlphaMode::Opaque;
        m.alpha_cutoff = std::isfinite(src.alphaCutoff) ? static_cast<float>(src.alphaCutoff) : 0.5f;
        m.base_color_texture = textureRef(who + " baseColorTexture", pbr.baseColorTexture.index,
                                          pbr.baseColorTexture.texCoord, 1.0, true);
        m.metallic_roughness_texture =
            textureRef(who + " metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
                       pbr.metallicRoughnessTexture.texCoord, 1.0, false);
        m.normal_texture = textureRef(who + " normalTexture", src.normalTexture.index,
                                      src.normalTexture.texCoord, src.normalTexture.scale, false);
        m.occlusion_texture = textureRef(who + " occlusionTexture", src.occlusionTexture.index,
                                         src.occlusionTexture.texCoord, src.occlusionTexture.strength, false);
        m.emissive_texture = textureRef(who + " emissiveTexture", src.emissiveTexture.index,
                                        src.emissiveTexture.texCoord, 1.0, true);
        scene_.materials.push_back(std::move(m));
    }
}

}  // namespace shaderlab::gltf_detail
