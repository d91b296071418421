#include "model_effect.hpp"

namespace dtwire::app {
namespace {

// Scales the initial imperfection amplitudes of the model (a bow of the column, or the local
// necking seed) by p.
class GeometryImperfection : public ModelEffect {
 public:
  std::string name() const override { return "geometry_imperfection"; }
  std::string unsupported(const ModelContext& context) const override {
    for (const char* path : kAmplitudes)
      if (context.number(path) != 0.0) return "";
    return "the .prm has no imperfection amplitude to scale";
  }
  void apply(double p, const ModelContext& context, PrmDocument& edited) const override {
    for (const char* path : kAmplitudes)
      if (context.number(path) != 0.0) edited.set(path, number_text(p * context.number(path)));
  }

 private:
  static constexpr const char* kAmplitudes[] = {"Geometry/Bow imperfection (mm)", "Geometry/Imperfection"};
};

}  // namespace

std::unique_ptr<ModelEffect> make_geometry_imperfection() { return std::make_unique<GeometryImperfection>(); }

}  // namespace dtwire::app
