#include "codec_tables.h"

#include <algorithm>
#include <iterator>

#include "encodings.h"

namespace gbl::enc {

const std::vector<float>& codecTableFloats() {
    static const std::vector<float> floats = [] {
        std::vector<float> f(kCodecTableFloats, 0.0f);
        auto put = [&](uint32_t offset, const float* first, const float* last) {
            std::copy(first, last, f.begin() + offset);
        };
        put(kCodecTableSrgbDecode, std::begin(kSrgbDecode), std::end(kSrgbDecode));
        put(kCodecTableSrgbEncode, std::begin(kSrgbEncodeThresholds), std::end(kSrgbEncodeThresholds));
        put(kCodecTableCryGlossDecode, std::begin(kCryGlossRoughness), std::end(kCryGlossRoughness));
        put(kCodecTableCryGlossEncode, std::begin(kCryGlossEncodeThresholds), std::end(kCryGlossEncodeThresholds));
        put(kCodecTableGamma22Decode, std::begin(kGamma22Decode), std::end(kGamma22Decode));
        put(kCodecTableGamma22Encode, std::begin(kGamma22EncodeThresholds), std::end(kGamma22EncodeThresholds));
        put(kCodecTableSrgbFastHdrpEncode, std::begin(kSrgbFastHdrpEncodeThresholds),
            std::end(kSrgbFastHdrpEncodeThresholds));
        put(kCodecTableKz2PowerDecode, std::begin(kKz2PowerRoughness), std::end(kKz2PowerRoughness));
        put(kCodecTableKz2PowerEncode, std::begin(kKz2PowerEncodeThresholds), std::end(kKz2PowerEncodeThresholds));
        return f;
    }();
    return floats;
}

}  // namespace gbl::enc
