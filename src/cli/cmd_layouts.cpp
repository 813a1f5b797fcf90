#include "cmd_layouts.h"

#include <algorithm>
#include <filesystem>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "encoding_registry.h"
#include "layout_atlas.h"
#include "layout_catalog.h"
#include "layout_coverage.h"
#include "layout_export.h"
#include "file_io.h"
#include "shader_compiler.h"
#include "best_fit_normals.h"
#include "wiring_codegen.h"

namespace gbl {

namespace {

constexpr const char* kUsage =
    "usage: gbufferlab layouts check [FILE...]   validate layout files (default: all in the layouts dir)\n"
    "       gbufferlab layouts list              the atlas: layouts by family, with year, bytes per pixel,\n"
    "                                            provenance (how much is verified in the engine's source), title\n"
    "       gbufferlab layouts show NAME|FILE    targets, bits per attribute, bytes per pixel, each entry's provenance\n"
    "       gbufferlab layouts glsl NAME|FILE [--native-formats]\n"
    "                                            print the generated GLSL wiring (writeGBuffer / readGBuffer)\n"
    "       gbufferlab layouts export NAME|FILE --lang hlsl|glsl [--kernel] [--tables selects|arrays]\n"
    "                                [--out FILE [--force]]\n"
    "                                            one self-contained HLSL or GLSL file for an engine: Surface struct,\n"
    "                                            encode to the real target formats, decode (docs/export.md); the\n"
    "                                            8-bit tables as select trees (default) or const arrays\n";

std::string pad(std::string s, size_t width) {
    if (s.size() < width) s.append(width - s.size(), ' ');
    return s;
}

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

std::string fallbackText(const Fallback& f) {
    switch (f.kind) {
        case FallbackKind::Constant: {
            std::string s;
            for (double v : f.value) s += (s.empty() ? "" : ", ") + number(v);
            return f.value.size() > 1 ? "(" + s + ")" : s;
        }
        case FallbackKind::FromMetallic:
            return "from_metallic: mix(0.04, base_color, metallic)";
        case FallbackKind::Ue4:
            return "ue4: mix(0.08 * specular, base_color, metallic)";
        case FallbackKind::FromBaseColor:
            return "from_base_color: base_color * (1 - metallic)";
        case FallbackKind::FromDiffuseSpecular:
            return "from_diffuse_specular: diffuse_color + metallic * specular_color";
        case FallbackKind::FromSpecularColor:
            return "from_specular_color: clamp((max3(specular_color) - 0.04) / 0.96, 0, 1)";
        case FallbackKind::FromRoughness:
            return "from_roughness: roughness";
        case FallbackKind::MaterialPass:
            return "material_pass: read by the material (second geometry) pass";
        case FallbackKind::Forward:
            return "forward: added to the lit output by the geometry pass, not stored";
    }
    return "?";
}

std::string placeText(const std::vector<Channel>& channels, const CodePlace& code) {
    std::string s;
    for (const BitRange& r : code.pieces) s += (s.empty() ? "" : " + ") + bitRangeText(channels, r);
    return s;
}

// Free bit ranges of a target / stencil, "b[4:7], a" style; "none" when full.
std::string unusedText(const std::vector<Channel>& channels, const std::vector<Field>& fields) {
    std::vector<std::vector<bool>> used(channels.size());
    for (size_t c = 0; c < channels.size(); ++c) used[c].assign(static_cast<size_t>(channels[c].bits), false);
    for (const Field& f : fields)
        for (const CodePlace& code : f.codes)
            for (const BitRange& r : code.pieces)
                for (int b = r.first; b < r.first + r.count && b < channels[r.channel].bits; ++b)
                    used[static_cast<size_t>(r.channel)][static_cast<size_t>(b)] = true;
    std::string s;
    int total = 0;
    for (size_t c = 0; c < channels.size(); ++c) {
        const int n = channels[c].bits;
        for (int b = 0; b < n;) {
            if (used[c][static_cast<size_t>(b)]) {
                ++b;
                continue;
            }
            int e = b;
            while (e < n && !used[c][static_cast<size_t>(e)]) ++e;
            const BitRange r{static_cast<int>(c), b, e - b};
            s += (s.empty() ? "" : ", ") + (r.count == n ? channels[c].name : bitRangeText(channels, r));
            total += e - b;
            b = e;
        }
    }
    return s.empty() ? "none" : s + " (" + std::to_string(total) + " bits)";
}

// An entry's provenance on one line: "verified  gbi:418-421; sgu:528"; "" when it has none.
std::string provenanceText(const Provenance& p) {
    if (!p.given()) return "";
    std::string s = provenanceStatusName(p.status);
    if (!p.from.empty()) s += "  " + p.from;
    return s;
}

// " [verified  gbi:335]" after a one-line entry, and its known difference on the next line.
void provenanceSuffix(std::ostream& o, const Provenance& p, const std::string& indent) {
    const std::string t = provenanceText(p);
    if (!t.empty()) o << "  [" << t << "]";
    o << "\n";
    if (!p.differs.empty()) o << indent << "differs: " << p.differs << "\n";
}

// The provenance of each field of a target (or the stencil), one line each, under its table.
void describeFieldProvenance(std::ostream& o, const std::vector<Field>& fields) {
    bool any = false;
    for (const Field& f : fields) any = any || f.provenance.given();
    if (!any) return;
    o << "  provenance:\n";
    for (const Field& f : fields) {
        o << "    " << pad(attributeName(f.attribute), 24) << provenanceText(f.provenance) << "\n";
        if (!f.provenance.differs.empty()) o << "      differs: " << f.provenance.differs << "\n";
    }
}

std::string valuesText(const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += (s.empty() ? "" : ", ") + number(x);
    return v.size() > 1 ? "(" + s + ")" : s;
}

void describeFields(std::ostream& o, const std::vector<Field>& fields, const std::vector<Channel>& channels) {
    o << "  " << pad("bits", 18) << pad("attribute", 28) << pad("code", 8) << pad("encoding", 28) << "width\n";
    for (const Field& f : fields) {
        for (size_t i = 0; i < f.codes.size(); ++i) {
            std::string attr = attributeName(f.attribute);
            if (!f.value.empty()) {
                const size_t k = std::min(i, f.value.size() - 1);
                attr += " = " + number(f.value[k]);
            }
            o << "  " << pad(placeText(channels, f.codes[i]), 18) << pad(attr, 28) << pad(codeLabel(f, i), 8)
              << pad(f.encoding, 28) << f.codes[i].bits();
            if (f.conditional()) o << "  under " << shadingModelNames(f.models);
            if (f.attribute == Attribute::ShadingModel) o << "  the selector";
            o << "\n";
        }
    }
    o << "  unused: " << unusedText(channels, fields) << "\n";
    describeFieldProvenance(o, fields);
}

}  // namespace

std::string describeLayout(const Layout& layout) {
    std::ostringstream o;
    o << layout.name << ": " << layout.title << "\n";
    o << "source:   " << layout.source.text() << "\n";
    o << "pipeline: " << pipelineName(layout.pipeline) << "\n";
    if (layout.pipeline == Pipeline::VisibilityBuffer) {
        o << "space:    none stored (the resolve rebuilds every attribute in world space)\n";
    } else {
        o << "space:    normals " << storedSpaceName(layout.space.normal);
        if (layout.stores(Attribute::Position)) o << ", position " << storedSpaceName(layout.space.position);
        provenanceSuffix(o, layout.space.provenance, "          ");
    }
    o << "file:     " << layout.sourceFile << "\n";
    const ProvenanceCounts counts = provenanceCounts(layout);
    if (counts.missing < counts.entries)
        o << "provenance: " << counts.text() << " (entries: depth, targets, fields, fallbacks, clear values, ...)\n";
    int targetBytes = 0;
    for (const Target& t : layout.targets) {
        targetBytes += t.bytes();
        o << "\ntarget " << t.name << "  " << t.format << "  " << t.bytes() << " bytes";
        provenanceSuffix(o, t.provenance, "  ");
        describeFields(o, t.fields, t.channels);
    }
    if (const VisibilityIds& ids = layout.ids; ids.declared) {
        targetBytes += ids.bytes();
        o << "\nids " << ids.format << "  " << ids.bytes() << " bytes  triangle bits 0.." << ids.triangleBits - 1
          << ", draw bits " << ids.triangleBits << ".." << ids.triangleBits + ids.drawBits - 1
          << (ids.clusterTriangles ? " (clusters of " + std::to_string(ids.clusterTriangles) + " triangles)"
                                   : std::string())
          << (ids.drawOffset ? " holding id + " + std::to_string(ids.drawOffset) + " (0 = none)" : std::string())
          << (ids.alphaMaskBit ? ", alpha-mask flag bit " + std::to_string((ids.depthWord >= 0 ? 32 : ids.bits) - 1)
                               : std::string())
          << (ids.depthWord >= 0 ? ", word 1: the depth's float bits (resolved by a 64-bit max)" : std::string());
        provenanceSuffix(o, ids.provenance, "  ");
    }
    if (const Field* sel = layout.selector()) {
        // layouts/README.md, "Shading models: the selector"
        o << "\nshading models (selector '" << (sel->codes.empty() ? "?" : sel->codes[0].text) << "', "
          << (sel->codes.empty() ? 0 : sel->codes[0].bits()) << " bits; a pixel is of the first named model whose "
          << "layer it carries, else default):\n";
        for (const ShadingModelInfo& m : listShadingModels())
            for (const Field::ModelId& id : sel->selector)
                if (id.model == m.id) {
                    std::string holds;
                    for (const Target& t : layout.targets)
                        for (const Field& f : t.fields)
                            if ((f.models >> unsigned(m.id)) & 1u)
                                holds += (holds.empty() ? "" : ", ") + std::string(attributeName(f.attribute));
                    o << "  " << pad(m.name, 14) << pad("id " + std::to_string(id.id), 8) << pad(m.meaning, 60)
                      << "holds: " << (holds.empty() ? "no conditional field" : holds) << "\n";
                }
    }
    const Depth& d = layout.depth;
    o << "\ndepth " << d.format << "  " << depthAttachmentBytes(layout) << " bytes  " << d.depthBits << "-bit "
      << (d.floatDepth ? "float" : "unorm") << (d.reversedZ ? ", reversed Z" : "")
      << (layout.ids.depthWord >= 0 ? ", in the ids' word 1 (no depth attachment)" : "");
    provenanceSuffix(o, d.provenance, "  ");
    if (d.stencilBits > 0) {
        const std::vector<Channel> channels = {{"s", d.stencilBits, 0, ChannelType::Uint}};
        describeFields(o, d.stencil, channels);
    }
    o << "\nbits per attribute:\n";
    for (const AttributeBits& ab : bitsPerAttribute(layout))
        // Stored per model under every model the selector names (ue5-clearcoat-normal's normal):
        // on every pixel, the widest field's bits.
        o << "  " << pad(attributeName(ab.attribute), 24) << ab.bits
          << (!ab.models ? std::string()
              : storesOnEveryModel(layout, ab.attribute)
                  ? "  (per model, at most: " + shadingModelNames(ab.models) + ")"
                  : "  (under " + shadingModelNames(ab.models) + " only)")
          << "\n";
    // What an encoding stores besides its attribute (HDRP's AO tag: occlusion in the g code).
    for (const Target& t : layout.targets)
        for (const Field& f : t.fields)
            if (const EncodingInfo* e = findEncoding(f.encoding); e && !e->carries.empty() && f.codes.size() > 1)
                o << "  " << pad(e->carries, 24) << f.codes[1].bits() << " (in " << attributeName(f.attribute)
                  << "'s " << f.encoding << ", where " << attributeName(f.attribute) << " is 0)\n";
    if (!layout.fallbacks.empty()) {
        o << "\nfallbacks (not stored):\n";
        for (const Fallback& f : layout.fallbacks) {
            o << "  " << pad(attributeName(f.attribute), 24) << fallbackText(f);
            if (layout.storesConditionally(f.attribute))
                o << "  (where the pixel's model stores none: not under "
                  << shadingModelNames(layout.conditionalModels(f.attribute)) << ")";
            provenanceSuffix(o, f.provenance, "    ");
        }
    }
    if (!layout.clears.empty()) {
        o << "\nclear (a pixel without geometry):\n";
        for (const ClearValue& c : layout.clears) {
            o << "  " << pad(attributeName(c.attribute), 24) << valuesText(c.value);
            provenanceSuffix(o, c.provenance, "    ");
        }
    }
    if (!layout.lightBuffers.empty()) {
        o << "\nlight buffers:\n";
        for (const LightBuffer& b : layout.lightBuffers) {
            std::string holds;
            for (LightQuantity q : b.holds) holds += (holds.empty() ? "" : " + ") + std::string(lightQuantityName(q));
            std::string encoding = lightBufferEncodingName(b.encoding);
            if (b.encoding == LightBufferEncoding::Rgbk) {
                char range[32];
                std::snprintf(range, sizeof range, "%g", b.range);
                encoding += std::string(" (range ") + range + ")";
            }
            o << "  " << pad(b.name, 16) << pad(b.format, 26) << pad(std::to_string(b.bytes) + " bytes", 10)
              << pad(encoding, 20) << holds;
            provenanceSuffix(o, b.provenance, "    ");
        }
        o << "  material pass: fresnel "
          << (layout.materialPass.fresnel == MaterialFresnel::SchlickNv ? "schlick_nv" : "none");
        provenanceSuffix(o, layout.materialPass.provenance, "    ");
    }
    o << "\nbytes per pixel: " << bytesPerPixel(layout) << " (targets " << targetBytes << " + depth-stencil " << depthAttachmentBytes(layout)
      << ")";
    if (!layout.lightBuffers.empty()) o << "; light buffers " << lightBufferBytesPerPixel(layout);
    o << "\n";
    if (!layout.citations.empty()) {
        o << "\nsources (" << (layout.citations.size() == 1 ? "1 citation" : std::to_string(layout.citations.size()) + " citations")
          << "; \"key:N\" cites line N of a file, or slide N of a talk, page N where it says unit = \"page\"):\n";
        size_t width = 0;
        for (const Citation& c : layout.citations) width = std::max(width, c.key.size());
        for (const Citation& c : layout.citations) o << "  " << pad(c.key, width + 2) << c.text() << "\n";
    }
    return o.str();
}

int checkLayoutsCommand(const std::vector<std::string>& files, std::ostream& out, std::ostream& err) {
    std::vector<std::string> list = files;
    if (list.empty()) {
        try {
            const auto dir = layoutDirectory();
            for (const std::string& name : listLayoutNames(dir)) list.push_back((dir / (name + ".toml")).string());
        } catch (const UserError& e) {
            err << e.what() << "\n";
            return 1;
        }
        if (list.empty()) {
            err << "no layout files to check\n";
            return 1;
        }
    }
    int bad = 0;
    for (const std::string& f : list) {
        const std::vector<LayoutDiagnostic> diags = checkLayoutFile(f);
        if (diags.empty()) {
            out << "ok " << f << "\n";
            continue;
        }
        ++bad;
        for (const LayoutDiagnostic& d : diags) err << d.text() << "\n";
    }
    if (bad) err << bad << " of " << list.size() << " layout files invalid\n";
    return bad ? 1 : 0;
}

// "25", "8 +16 light" (deferred lighting's light buffers), "12 ids" (a pipeline whose targets hold ids).
std::string atlasBytesText(const AtlasEntry& e) {
    std::string s = std::to_string(e.bytesPerPixel);
    if (e.bytesKind != "attributes") s += " " + e.bytesKind;
    if (e.lightBufferBytesPerPixel > 0) s += " +" + std::to_string(e.lightBufferBytesPerPixel) + " light";
    return s;
}

int listLayoutsCommand(std::ostream& out, std::ostream& err) {
    std::filesystem::path dir;
    std::vector<std::string> names;
    try {
        dir = layoutDirectory();
        names = listLayoutNames(dir);
    } catch (const UserError& e) {
        err << e.what() << "\n";
        return 1;
    }
    std::vector<AtlasEntry> entries;
    std::vector<std::string> invalid;
    for (const std::string& name : names) {
        try {
            entries.push_back(atlasEntryOf(loadLayoutFile(dir / (name + ".toml"))));
        } catch (const UserError& e) {
            invalid.push_back(name);
            err << e.what() << "\n";
        }
    }
    // Grouped as the report's atlas table (layout_atlas.h): family, then its layouts by year.
    // Provenance: how many of the layout's entries are verified in the engine's source (layout.h);
    // its column is as wide as its longest text.
    size_t provenanceWidth = std::string("provenance").size();
    for (const AtlasEntry& e : entries) provenanceWidth = std::max(provenanceWidth, e.provenance.text().size());
    provenanceWidth += 2;
    out << pad("family / layout", 26) << pad("year", 6) << pad("bytes/px", 16) << pad("provenance", provenanceWidth)
        << "title\n";
    for (const AtlasGroup& g : groupAtlas(std::move(entries))) {
        out << g.family << "\n";
        for (const AtlasEntry& e : g.entries)
            out << "  " << pad(e.layout, 24) << pad(std::to_string(e.year), 6) << pad(atlasBytesText(e), 16)
                << pad(e.provenance.text(), provenanceWidth) << e.title << "\n";
    }
    if (!invalid.empty()) {
        out << "(invalid: run `gbufferlab layouts check`)\n";
        for (const std::string& name : invalid) out << "  " << name << "\n";
    }
    return invalid.empty() ? 0 : 1;
}

int showLayoutCommand(const std::string& nameOrPath, std::ostream& out, std::ostream& err) {
    try {
        out << describeLayout(loadLayout(nameOrPath));
        return 0;
    } catch (const UserError& e) {
        err << e.what() << "\n";
        return 1;
    }
}

int printLayoutGlslCommand(const std::string& nameOrPath, bool nativeFormats, std::ostream& out, std::ostream& err) {
    try {
        WiringOptions options;
        options.nativeFormats = nativeFormats;
        const Layout layout = loadLayout(nameOrPath);
        out << "// file: " << escapeText(layout.sourceFile) << "\n" << generateWiringGlsl(layout, options);
        return 0;
    } catch (const UserError& e) {
        err << e.what() << "\n";
        return 1;
    }
}

// `layouts export`: stdout, or --out FILE (never over an existing file without --force, never
// over the layout read; written through a temporary, so a failure leaves no partial file).
int exportLayoutCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    std::string input, lang, outPath, tables = "selects";
    bool kernel = false, force = false, outGiven = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if ((a == "--lang" || a == "--out" || a == "--tables") && i + 1 < args.size()) {
            outGiven = outGiven || a == "--out";
            (a == "--lang" ? lang : a == "--out" ? outPath : tables) = args[++i];
        } else if (a.rfind("--tables=", 0) == 0) {
            tables = a.substr(9);
        } else if (a.rfind("--lang=", 0) == 0) {
            lang = a.substr(7);
        } else if (a.rfind("--out=", 0) == 0) {
            outGiven = true;
            outPath = a.substr(6);
        } else if (a == "--kernel") {
            kernel = true;
        } else if (a == "--force") {
            force = true;
        } else if (a.rfind("--", 0) == 0 || !input.empty()) {
            err << "gbufferlab layouts export: unexpected argument '" << escapeText(a) << "'\n" << kUsage;
            return 2;
        } else {
            input = a;
        }
    }
    if (input.empty() || (lang != "hlsl" && lang != "glsl")) {
        err << "gbufferlab layouts export: give a layout and --lang hlsl or --lang glsl\n" << kUsage;
        return 2;
    }
    if (tables != "selects" && tables != "arrays") {
        err << "gbufferlab layouts export: --tables '" << escapeText(tables)
            << "': unknown (selects: select trees, every driver compiles them fast; arrays: const arrays, "
               "fewer instructions on a GPU)\n";
        return 2;
    }
    try {
        // --out "" names no file: an error (as any bad output path), never standard output.
        if (outGiven && outPath.empty())
            throwUserError("--out '': an empty file name; give a file name, or leave --out out to print to standard "
                           "output");
        const Layout layout = loadLayout(input);
        ExportOptions options;
        options.language = lang == "hlsl" ? ExportLanguage::Hlsl : ExportLanguage::Glsl;
        options.kernel = kernel;
        options.tables = tables == "arrays" ? exporting::ExportTables::Arrays : exporting::ExportTables::Selects;
        const std::string text = exportLayout(layout, options, [](const std::string& name) {
            return resolveShaderInclude(name, {});
        });
        if (outPath.empty()) {
            out << text;
            return 0;
        }
        const std::vector<std::string> inputs = {layout.sourceFile};
        refuseOutputOverInput(outPath, inputs, "--out");
        const std::string table = outPath + ".bestfit.u32";
        const bool needsTable = exportUsesBestFitTable(layout);
        for (const std::string& p : needsTable ? std::vector<std::string>{outPath, table} : std::vector<std::string>{outPath}) {
            refuseNonRegularOutput(p, "--out");  // a device, FIFO or socket: never replaced, --force or not
            if (std::filesystem::exists(p) && !force)
                throwUserError("--out " + escapeText(p) + ": file exists; choose another name or add --force to replace it");
        }
        if (needsTable) {
            refuseOutputOverInput(table, inputs, "--out");
            const std::vector<uint32_t>& words = enc::bestFitNormalTable();
            writeFileAtomic(table, words.data(), words.size() * sizeof(uint32_t));
        }
        writeFileAtomic(outPath, text);
        out << "wrote " << escapeText(outPath) << (needsTable ? " and " + escapeText(table) : "") << "\n";
        return 0;
    } catch (const UserError& e) {
        err << e.what() << "\n";
        return 1;
    } catch (const std::runtime_error& e) {
        err << "gbufferlab layouts export: " << e.what() << "\n";
        return 1;
    }
}

int runLayoutsCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    if (!args.empty() && args[0] == "glsl") {
        std::vector<std::string> rest(args.begin() + 1, args.end());
        const auto flag = std::find(rest.begin(), rest.end(), "--native-formats");
        const bool native = flag != rest.end();
        if (native) rest.erase(flag);
        if (rest.size() == 1) return printLayoutGlslCommand(rest[0], native, out, err);
    }
    if (!args.empty() && args[0] == "export")
        return exportLayoutCommand(std::vector<std::string>(args.begin() + 1, args.end()), out, err);
    if (!args.empty() && args[0] == "check")
        return checkLayoutsCommand(std::vector<std::string>(args.begin() + 1, args.end()), out, err);
    if (args.size() == 1 && args[0] == "list") return listLayoutsCommand(out, err);
    if (args.size() == 2 && args[0] == "show") return showLayoutCommand(args[1], out, err);
    err << kUsage;
    return 2;
}

}  // namespace gbl
