#include "mesh/scene/material_presets.h"

namespace rad {
namespace {

// The widely published OpenGL/VRML material table; shininess is on OpenGL's 0-128 scale.
const MaterialPreset kPresets[] = {
    {"black_plastic", {0.0, 0.0, 0.0, 1.0}, {0.01, 0.01, 0.01, 1.0}, {0.50, 0.50, 0.50, 1.0}, 32.0},
    {"brass", {0.329412, 0.223529, 0.027451, 1.0}, {0.780392, 0.568627, 0.113725, 1.0},
     {0.992157, 0.941176, 0.807843, 1.0}, 27.8974},
    {"bronze", {0.2125, 0.1275, 0.054, 1.0}, {0.714, 0.4284, 0.18144, 1.0},
     {0.393548, 0.271906, 0.166721, 1.0}, 25.6},
    {"chrome", {0.25, 0.25, 0.25, 1.0}, {0.4, 0.4, 0.4, 1.0}, {0.774597, 0.774597, 0.774597, 1.0},
     76.8},
    {"copper", {0.19125, 0.0735, 0.0225, 1.0}, {0.7038, 0.27048, 0.0828, 1.0},
     {0.256777, 0.137622, 0.086014, 1.0}, 12.8},
    {"gold", {0.24725, 0.1995, 0.0745, 1.0}, {0.75164, 0.60648, 0.22648, 1.0},
     {0.628281, 0.555802, 0.366065, 1.0}, 51.2},
    {"pewter", {0.105882, 0.058824, 0.113725, 1.0}, {0.427451, 0.470588, 0.541176, 1.0},
     {0.333333, 0.333333, 0.521569, 1.0}, 9.84615},
    {"silver", {0.19225, 0.19225, 0.19225, 1.0}, {0.50754, 0.50754, 0.50754, 1.0},
     {0.508273, 0.508273, 0.508273, 1.0}, 51.2},
    {"polished_silver", {0.23125, 0.23125, 0.23125, 1.0}, {0.2775, 0.2775, 0.2775, 1.0},
     {0.773911, 0.773911, 0.773911, 1.0}, 89.6},
};

}  // namespace

const MaterialPreset* findMaterialPreset(const std::string& name) {
  for (const auto& p : kPresets)
    if (name == p.name) return &p;
  return nullptr;
}

std::vector<std::string> materialPresetNames() {
  std::vector<std::string> names;
  for (const auto& p : kPresets) names.push_back(p.name);
  return names;
}

}  // namespace rad
