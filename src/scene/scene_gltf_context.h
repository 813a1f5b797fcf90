#pragma once
// What every part of the glTF loader needs: the parsed model and the file name for errors.
#include <string>

#include <tiny_gltf.h>

#include "error.h"

namespace gbl {

struct GltfContext {
    std::string path;
    const tinygltf::Model& model;

    // Throws the one-line UserError of the error policy: "<file>: <where>: <problem>; <fix>".
    // Names inside the file may hold newlines; they are flattened to keep the message one line.
    [[noreturn]] void fail(const std::string& where, const std::string& problem, const std::string& fix) const {
        std::string message = formatPlace(path) + ": " + where + ": " + problem + "; " + fix;
        for (char& c : message)
            if (c == '\n' || c == '\r' || c == '\t') c = ' ';
        throwUserError(message);
    }
};

// "mesh 3 ('Wheel') primitive 1": names help find the object in a DCC tool.
inline std::string describeItem(const std::string& kind, size_t index, const std::string& name) {
    std::string text = kind + " " + std::to_string(index);
    if (!name.empty()) text += " ('" + name + "')";
    return text;
}

}  // namespace gbl
