#pragma once
// The fixed-function lighting state of the OSMesa passes: the scene's lights, light model and
// fog, and the materials of the local and hybrid models. Each call needs a current OSMesa
// context, with the view matrix loaded (OpenGL fixes light positions in eye coordinates then).
// Not a public header.
#include "display/viewer/viewer.h"
#include "mesh/scene/scene.h"

namespace rad::viewer::detail {

/// The local model's lighting: the scene's lights, normalised normals, material colours (not
/// vertex colours), and its fog. Throws std::runtime_error when OpenGL has too few lights.
void enableLocalLighting(const Scene& scene);

/// The hybrid model's lighting: the scene's lights adding only the specular term, as a separate
/// colour, to the vertex colour taken as the emission (material ambient and diffuse zero).
/// Throws std::runtime_error when OpenGL has too few lights.
void enableSpecularLighting(const Scene& scene);

/// Every material of the local model: ambient, diffuse, specular, emission and shininess.
void setLocalMaterial(const LocalBatch& b);

/// The hybrid model's materials: specular colour and shininess only.
void setSpecularMaterial(const LocalBatch& b);

}  // namespace rad::viewer::detail
