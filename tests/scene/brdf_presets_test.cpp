// Tests of scene/brdf_presets.h: the fit table against brdf-reference.md section 3.1 (read from
// the document itself), names and aliases, the MERL colour switch, and energy bounds.
#include "scene/brdf_presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "shade/brdf_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int presets_sample_scale = 10;
#else
constexpr int presets_sample_scale = 1;
#endif

/// One row of the document's table 3.1, numbers as written.
struct DocRow {
    std::string material, model;
    std::vector<std::string> rho_d, rho_s;
    std::string lobe_name, lobe;
};

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, sep)) {
        const size_t a = item.find_first_not_of(' '), b = item.find_last_not_of(' ');
        out.push_back(a == std::string::npos ? "" : item.substr(a, b - a + 1));
    }
    return out;
}

/// The rows of the table under "### 3.1" in brdf-reference.md.
std::vector<DocRow> read_table_3_1() {
    std::ifstream file(std::string(RAYLANE_SHARED_DIR) + "/docs/brdf-reference.md");
    std::vector<DocRow> rows;
    std::string line;
    bool in_section = false;
    while (std::getline(file, line)) {
        if (line.rfind("### ", 0) == 0) in_section = line.rfind("### 3.1", 0) == 0;
        if (!in_section || line.rfind("| ", 0) != 0) continue;
        const std::vector<std::string> cells = split(line.substr(1), '|');
        if (cells.size() < 5 || cells[0] == "material" || cells[0].rfind("---", 0) == 0) continue;
        DocRow row{cells[0], cells[1], split(cells[2], ','), split(cells[3], ','), "", ""};
        const std::vector<std::string> lobe = split(cells[4], '=');
        if (lobe.size() == 2) row.lobe_name = lobe[0], row.lobe = lobe[1];
        rows.push_back(row);
    }
    return rows;
}

SpecularModel model_named(const std::string& name) {
    if (name == "Ward-Duer") return SpecularModel::ward_duer;
    if (name == "Blinn-Phong") return SpecularModel::blinn_phong;
    EXPECT_EQ(name, "Ward");
    return SpecularModel::ward;
}

TEST(BrdfPresets, MatchTheReferenceTableDigitForDigit) {
    const std::vector<DocRow> rows = read_table_3_1();
    ASSERT_EQ(rows.size(), 9u) << "table 3.1 of brdf-reference.md";
    ASSERT_EQ(brdf_fits().size(), 9u);
    for (const DocRow& row : rows) {
        const SpecularModel model = model_named(row.model);
        const BrdfFit* fit = nullptr;
        for (const BrdfFit& f : brdf_fits())
            if (f.material == row.material && f.model == model) fit = &f;
        ASSERT_NE(fit, nullptr) << row.material << " " << row.model;
        ASSERT_EQ(row.rho_d.size(), 3u);
        ASSERT_EQ(row.rho_s.size(), 3u);
        for (int c = 0; c < 3; ++c) {
            // the same decimal string parses to the same float: equality is digit for digit
            EXPECT_EQ(fit->rho_d[c], std::stof(row.rho_d[size_t(c)])) << row.material << row.model;
            EXPECT_EQ(fit->rho_s[c], std::stof(row.rho_s[size_t(c)])) << row.material << row.model;
        }
        EXPECT_EQ(row.lobe_name, model == SpecularModel::blinn_phong ? "n" : "alpha");
        EXPECT_EQ(fit->lobe, std::stof(row.lobe)) << row.material << " " << row.model;

        // and apply_brdf_preset copies the row into a material
        Material m;
        m.model = model;
        m.k_a = 0.3f;
        m.k_d = 0.2f;
        m.k_s = 0.7f;
        ASSERT_TRUE(apply_brdf_preset(row.material, m));
        EXPECT_EQ(m.c_d, fit->rho_d);
        EXPECT_EQ(m.c_s, fit->rho_s);
        EXPECT_EQ(m.k_d, 1.0f);
        EXPECT_EQ(m.k_a, 0.0f);
        EXPECT_EQ(m.k_s, 1.0f);
        EXPECT_EQ(model == SpecularModel::blinn_phong ? m.exponent : m.alpha, fit->lobe);
    }
}

TEST(BrdfPresets, AcceptTheReportsNamesAndAliases) {
    const std::vector<std::string> names = brdf_preset_names();
    EXPECT_EQ(names, (std::vector<std::string>{"nickel", "acrylic-green", "delrin"}));
    for (const std::string& name : names) {
        Material m;
        m.model = SpecularModel::ward;
        EXPECT_TRUE(apply_brdf_preset(name, m)) << name;
    }
    Material a, b;
    a.model = b.model = SpecularModel::ward_duer;
    ASSERT_TRUE(apply_brdf_preset("acrylic-green", a));
    ASSERT_TRUE(apply_brdf_preset("green-acrylic", b));
    EXPECT_EQ(a.c_d, b.c_d);
    EXPECT_EQ(a.alpha, 0.0137f);
    ASSERT_TRUE(apply_brdf_preset("derlin", b));  // the report's spelling
    EXPECT_EQ(b.alpha, 0.146f);
}

TEST(BrdfPresets, RejectUnknownNamesAndModelsWithoutFits) {
    Material m;
    m.model = SpecularModel::ward;
    m.c_d = vec3(0.5f);
    m.alpha = 0.25f;
    EXPECT_FALSE(apply_brdf_preset("gold", m));
    EXPECT_FALSE(apply_brdf_preset("Nickel", m));
    EXPECT_FALSE(apply_brdf_preset("", m));
    for (SpecularModel model : {SpecularModel::phong, SpecularModel::glossy_phong}) {
        m.model = model;
        EXPECT_FALSE(apply_brdf_preset("nickel", m));
    }
    EXPECT_EQ(m.c_d, vec3(0.5f)) << "a rejected preset leaves the material alone";
    EXPECT_EQ(m.alpha, 0.25f);
}

TEST(BrdfPresets, MerlColourScalesGreenByOneFifteenAndBlueByOneSixtySix) {
    for (const BrdfFit& fit : brdf_fits()) {
        Material plain, merl;
        plain.model = merl.model = fit.model;
        ASSERT_TRUE(apply_brdf_preset(fit.material, plain));
        ASSERT_TRUE(apply_brdf_preset(fit.material, merl, true));
        EXPECT_EQ(merl.c_d.x, plain.c_d.x);
        EXPECT_EQ(merl.c_s.x, plain.c_s.x);
        EXPECT_FLOAT_EQ(merl.c_d.y, plain.c_d.y * 1.15f);
        EXPECT_FLOAT_EQ(merl.c_s.y, plain.c_s.y * 1.15f);
        EXPECT_FLOAT_EQ(merl.c_d.z, plain.c_d.z * 1.66f);
        EXPECT_FLOAT_EQ(merl.c_s.z, plain.c_s.z * 1.66f);
    }
    // brdf-reference.md 2.5: delrin's highlights become neutral
    Material m;
    m.model = SpecularModel::ward;
    ASSERT_TRUE(apply_brdf_preset("delrin", m, true));
    EXPECT_NEAR(m.c_s.x, 0.0348f, 5e-5f);
    EXPECT_NEAR(m.c_s.y, 0.0339f, 5e-5f);
    EXPECT_NEAR(m.c_s.z, 0.0335f, 5e-5f);
    m.model = SpecularModel::blinn_phong;
    ASSERT_TRUE(apply_brdf_preset("delrin", m, true));
    EXPECT_NEAR(m.c_s.x, 0.00755f, 5e-6f);
    EXPECT_NEAR(m.c_s.y, 0.00752f, 5e-6f);
    EXPECT_NEAR(m.c_s.z, 0.00765f, 5e-6f);
}

TEST(BrdfPresets, PeakHighlightsMatchTheQuickScaleFacts) {
    // brdf-reference.md 3.3: peak specular BRDF value at normal incidence, red channel
    struct Case {
        const char* name;
        SpecularModel model;
        float peak;
    };
    const vec3 n(0, 0, 1);
    for (const Case& c : {Case{"nickel", SpecularModel::ward, 8.70f},
                          Case{"nickel", SpecularModel::blinn_phong, 11.0f},
                          Case{"acrylic-green", SpecularModel::ward, 4.04f},
                          Case{"delrin", SpecularModel::ward, 0.106f}}) {
        Material m;
        m.model = c.model;
        ASSERT_TRUE(apply_brdf_preset(c.name, m));
        // report scaling = rho_s S (no cosine), i.e. the BRDF's specular part
        const float peak = specular_factor(m, BrdfScaling::report, n, n, n).x;
        EXPECT_NEAR(peak, c.peak, 0.006f * c.peak) << c.name;
    }
}

TEST(BrdfPresets, FittedMaterialsReflectNoMoreThanTheyReceive) {
    // directional albedo rho_d + rho_s A(theta_o) <= 1 per channel, theta_o up to 80 degrees
    // (brdf-reference.md 7.3), physical scaling, by importance sampling the specular lobe
    std::mt19937_64 rng(42);
    auto uniform = [&rng] { return static_cast<float>(rng() >> 40) * 0x1.0p-24f; };
    const vec3 n(0, 0, 1);
    const int count = 50000 / presets_sample_scale;
    for (const BrdfFit& fit : brdf_fits()) {
        Material m;
        m.model = fit.model;
        ASSERT_TRUE(apply_brdf_preset(fit.material, m));
        for (double deg : {0.0, 30.0, 60.0, 75.0, 80.0}) {
            const float theta = float(deg * 3.14159265358979 / 180.0);
            const vec3 wo(std::sin(theta), 0.0f, std::cos(theta));
            double a = 0, a2 = 0;
            for (int i = 0; i < count; ++i) {
                const float u1 = uniform(), u2 = uniform();
                const LobeSample s = m.model == SpecularModel::ward
                                         ? sample_ward(n, wo, m.alpha, u1, u2)
                                     : m.model == SpecularModel::ward_duer
                                         ? sample_ward_duer(n, wo, m.alpha, u1, u2)
                                         : sample_blinn_phong(n, wo, m.exponent, u1, u2);
                a += s.weight, a2 += double(s.weight) * s.weight;
            }
            const double mean = a / count, se = std::sqrt((a2 / count - mean * mean) / count);
            for (int c = 0; c < 3; ++c) {
                const double albedo = m.c_d[c] + m.c_s[c] * mean;
                EXPECT_LT(albedo - 4 * m.c_s[c] * se, 1.0) << fit.material << " " << deg;
                EXPECT_GT(albedo, 0.0);
            }
        }
    }
}

}  // namespace
}  // namespace raylane
