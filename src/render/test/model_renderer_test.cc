// One ModelRenderer serves model after model: models that differ only in what is drawn per
// frame share its render context (render/context_key.h), and the pictures are exactly those of
// a renderer made for each model; a model that differs in what the context holds (a plane's
// size, a texture, the extent) gets a context of its own.
#include "render/model_renderer.h"

#include <gtest/gtest.h>

#include <string>

#include "render/context_key.h"
#include "render/egl_context.h"
#include "render/mujoco_model.h"

namespace prs::render {
namespace {

// A lit box on a ground plane, seen by a fixed camera; `box` and `plane` are the geoms'
// sizes, `extent` the model's (0: MuJoCo computes it), `texture` adds a checker texture.
std::string Scene(const std::string& box_pos, const std::string& plane = "0 0 0.05",
                  double extent = 3, bool texture = false) {
  std::string xml = "<mujoco>\n";
  if (texture) {
    xml +=
        "  <asset><texture name=\"grid\" type=\"2d\" builtin=\"checker\" width=\"64\" "
        "height=\"64\" rgb1=\"0.2 0.3 0.4\" rgb2=\"0.8 0.8 0.8\"/>\n"
        "  <material name=\"grid\" texture=\"grid\" texrepeat=\"4 4\"/></asset>\n";
  }
  xml += "  <worldbody>\n    <light pos=\"0 0 3\" dir=\"0 0 -1\" directional=\"true\"/>\n";
  xml += "    <geom type=\"plane\" size=\"" + plane + "\" rgba=\"0.9 0.9 0.9 1\"" +
         (texture ? " material=\"grid\"" : "") + "/>\n";
  xml += "    <body pos=\"" + box_pos +
         "\"><geom type=\"box\" size=\"0.1 0.1 0.1\" rgba=\"0.1 0.2 0.9 1\"/></body>\n";
  xml += "    <camera name=\"eye\" pos=\"0 -1.5 1.2\" xyaxes=\"1 0 0 0 0.6 0.8\"/>\n";
  xml += "  </worldbody>\n";
  if (extent > 0) xml += "  <statistic extent=\"" + std::to_string(extent) + "\"/>\n";
  xml += "</mujoco>\n";
  return xml;
}

struct Picture {
  Image rgb;
  DepthImage depth;
};

Picture Shoot(ModelRenderer& renderer, const mjModel& model) {
  renderer.SetModel(model);
  DataPtr data = MakeData(model);
  mj_forward(&model, data.get());
  Picture p;
  p.rgb = renderer.Render(*data, 0, &p.depth);
  return p;
}

Picture ShootFresh(const mjModel& model) {
  ModelRenderer renderer(model, 160, 120);
  return Shoot(renderer, model);
}

void ExpectSame(const Picture& a, const Picture& b, const std::string& what) {
  EXPECT_EQ(a.rgb.rgb, b.rgb.rgb) << what;
  EXPECT_EQ(a.depth.depth_m, b.depth.depth_m) << what;
}

TEST(ModelRendererTest, OneContextServesModelsThatDifferOnlyInPoses) {
  const ModelPtr a = LoadModelFromXml(Scene("0 0 0.1"));
  const ModelPtr b = LoadModelFromXml(Scene("0.3 0.2 0.1"));
  EXPECT_EQ(CalcRenderContextKey(*a), CalcRenderContextKey(*b));
  ModelRenderer shared(160, 120);
  const Picture first = Shoot(shared, *a);
  const Picture second = Shoot(shared, *b);  // drawn with a's context
  const Picture again = Shoot(shared, *a);
  EXPECT_NE(first.rgb.rgb, second.rgb.rgb) << "the box moved";
  ExpectSame(first, ShootFresh(*a), "a");
  ExpectSame(second, ShootFresh(*b), "b with a's context");
  ExpectSame(again, first, "a again");
}

TEST(ModelRendererTest, ModelsThatDifferInTheContextGetTheirOwn) {
  const ModelPtr base = LoadModelFromXml(Scene("0 0 0.1"));
  const std::string base_key = CalcRenderContextKey(*base);
  struct Case {
    std::string what;
    std::string xml;
  };
  const Case cases[] = {
      {"a finite ground plane", Scene("0 0 0.1", "1 1 0.05")},
      {"another extent (an infinite plane's grid, the shadow clip)",
       Scene("0 0 0.1", "0 0 0.05", 5)},
      {"a texture", Scene("0 0 0.1", "0 0 0.05", 3, true)},
  };
  for (const Case& c : cases) {
    const ModelPtr other = LoadModelFromXml(c.xml);
    EXPECT_NE(CalcRenderContextKey(*other), base_key) << c.what;
    ModelRenderer shared(160, 120);
    Shoot(shared, *base);
    const Picture switched = Shoot(shared, *other);
    ExpectSame(switched, ShootFresh(*other), c.what);
    const Picture back = Shoot(shared, *base);
    ExpectSame(back, ShootFresh(*base), c.what + ", then back");
  }
}

// Contexts made one after another take Mesa's two displays in turn (render/egl_context.h), so
// that two threads draw at once; both displays are llvmpipe and draw the same pixels.
TEST(ModelRendererTest, ContextsTakeTwoDisplaysInTurnAndDrawTheSamePictures) {
  {
    const internal::EglContext first, second, third;
    EXPECT_NE(first.display(), second.display())
        << "one display for all: two threads' pictures would wait for each other";
    EXPECT_EQ(first.display(), third.display());
  }
  const ModelPtr model = LoadModelFromXml(Scene("0.2 -0.1 0.1"));
  const Picture on_one = ShootFresh(*model);
  const Picture on_other = ShootFresh(*model);
  ExpectSame(on_one, on_other, "the two displays");
}

}  // namespace
}  // namespace prs::render
