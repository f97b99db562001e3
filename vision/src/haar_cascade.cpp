// Reader of OpenCV's cascade XML (METHOD.md §3): just the subset the cascade files use (elements,
// character data, comments, the <?xml?> declaration, attributes that are skipped), into a small
// element tree, then into HaarCascade. Start-up only: allocates, throws with one clear line.

#include "vision/haar_cascade.hpp"

#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <type_traits>

namespace vision {
namespace {

constexpr int kMaxWindow = 64;  // OpenCV's face cascades use 20x20 and 24x24 windows

struct Element {
    std::string name;
    int line = 0;
    std::string text;  // character data directly inside this element
    std::vector<std::unique_ptr<Element>> children;

    const Element* child(std::string_view n) const
    {
        for (const auto& c : children) {
            if (c->name == n)
                return c.get();
        }
        return nullptr;
    }
};

class Reader {
public:
    Reader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

    [[noreturn]] void fail(int line, const std::string& what) const
    {
        throw std::runtime_error("cascade " + name_ + ": line " + std::to_string(line) + ": " +
                                 what);
    }

    std::unique_ptr<Element> document()
    {
        skipMisc();
        if (pos_ >= text_.size())
            fail(line_, "expected an XML element, found end of file");
        if (text_[pos_] != '<')
            fail(line_, "expected an XML element");
        auto root = element();
        skipMisc();
        if (pos_ < text_.size())
            fail(line_, "unexpected content after the root element");
        return root;
    }

private:
    bool startsWith(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }

    void advance(std::size_t n)
    {
        for (std::size_t i = 0; i < n && pos_ < text_.size(); ++i, ++pos_) {
            if (text_[pos_] == '\n')
                ++line_;
        }
    }

    void skipUntil(std::string_view end, const char* what)
    {
        const int startLine = line_;
        const std::size_t at = text_.find(end, pos_);
        if (at == std::string_view::npos)
            fail(startLine, std::string("unterminated ") + what);
        advance(at + end.size() - pos_);
    }

    // Whitespace, comments and processing instructions between elements.
    void skipMisc()
    {
        for (;;) {
            while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
                advance(1);
            }
            if (startsWith("<!--")) {
                skipUntil("-->", "comment");
            } else if (startsWith("<?")) {
                skipUntil("?>", "declaration");
            } else {
                return;
            }
        }
    }

    std::string nameAt()
    {
        const std::size_t start = pos_;
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
                c == ':') {
                ++pos_;
            } else {
                break;
            }
        }
        return std::string(text_.substr(start, pos_ - start));
    }

    std::unique_ptr<Element> element(int depth = 1)
    {
        // The reader recurses per level: a bound keeps a hostile file from exhausting the stack.
        if (depth > kMaxDepth)
            fail(line_, "elements nested deeper than " + std::to_string(kMaxDepth) + " levels");
        auto e = std::make_unique<Element>();
        e->line = line_;
        advance(1);  // '<'
        e->name = nameAt();
        if (e->name.empty())
            fail(line_, "expected an element name after '<'");
        // Attributes (type_id="...") carry nothing we need: skip to the end of the tag.
        while (pos_ < text_.size() && text_[pos_] != '>') {
            if (text_[pos_] == '"') {
                advance(1);
                skipUntil("\"", "attribute value");
            } else {
                advance(1);
            }
        }
        if (pos_ >= text_.size())
            fail(e->line, "unexpected end of file inside <" + e->name + ">");
        if (text_[pos_ - 1] == '/') {
            advance(1);
            return e;
        }
        advance(1);  // '>'
        for (;;) {
            if (pos_ >= text_.size()) {
                fail(line_, "unexpected end of file: <" + e->name + "> of line " +
                                std::to_string(e->line) + " is not closed");
            }
            if (startsWith("<!--")) {
                skipUntil("-->", "comment");
            } else if (startsWith("</")) {
                advance(2);
                const std::string closing = nameAt();
                if (closing != e->name)
                    fail(line_, "expected </" + e->name + ">");
                while (pos_ < text_.size() && text_[pos_] != '>')
                    advance(1);
                if (pos_ >= text_.size())
                    fail(line_, "unexpected end of file in </" + closing);
                advance(1);
                return e;
            } else if (text_[pos_] == '<') {
                e->children.push_back(element(depth + 1));
            } else {
                const std::size_t next = text_.find('<', pos_);
                const std::size_t end = next == std::string_view::npos ? text_.size() : next;
                e->text.append(text_.substr(pos_, end - pos_));
                advance(end - pos_);
            }
        }
    }

    static constexpr int kMaxDepth = 32;  // OpenCV's cascades nest 6 levels

    std::string_view text_;
    const std::string& name_;
    std::size_t pos_ = 0;
    int line_ = 1;
};

// Whitespace-separated numbers of an element's text.
class Numbers {
public:
    Numbers(const Element& e, const Reader& r) : e_(e), r_(r), s_(e.text) {}

    template <typename T>
    T next()
    {
        while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_])))
            ++pos_;
        if (pos_ >= s_.size())
            r_.fail(e_.line, "expected more numbers in <" + e_.name + ">");
        std::size_t end = pos_;
        while (end < s_.size() && !std::isspace(static_cast<unsigned char>(s_[end])))
            ++end;
        const std::string token = s_.substr(pos_, end - pos_);
        pos_ = end;
        T value{};
        if constexpr (std::is_integral_v<T>) {
            const auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
            if (ec != std::errc() || p != token.data() + token.size()) {
                r_.fail(e_.line, "expected an integer in <" + e_.name + ">, found '" + token + "'");
            }
        } else {
            // strtod accepts "2." and "-1." as the files write them; from_chars would too, but
            // strtod is what the file's writer (OpenCV's FileStorage) pairs with.
            char* stop = nullptr;
            const double d = std::strtod(token.c_str(), &stop);
            if (stop != token.c_str() + token.size() || !std::isfinite(d)) {
                r_.fail(e_.line, "expected a number in <" + e_.name + ">, found '" + token + "'");
            }
            value = static_cast<T>(d);
        }
        return value;
    }

    bool atEnd()
    {
        while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_])))
            ++pos_;
        return pos_ >= s_.size();
    }

private:
    const Element& e_;
    const Reader& r_;
    const std::string& s_;
    std::size_t pos_ = 0;
};

const Element& need(const Element& parent, std::string_view name, const Reader& r)
{
    const Element* c = parent.child(name);
    if (c == nullptr) {
        r.fail(parent.line, "expected <" + std::string(name) + "> in <" + parent.name + ">");
    }
    return *c;
}

std::string trimmed(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
        return {};
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}

template <typename T>
T single(const Element& parent, std::string_view name, const Reader& r)
{
    const Element& e = need(parent, name, r);
    Numbers n(e, r);
    const T v = n.template next<T>();
    if (!n.atEnd())
        r.fail(e.line, "expected one number in <" + e.name + ">");
    return v;
}

}  // namespace

bool HaarCascade::stumpsOnly() const noexcept
{
    for (const HaarWeakClassifier& w : weak) {
        if (w.nodeCount != 1)
            return false;
    }
    return true;
}

HaarCascade parseHaarCascade(std::string_view text, const std::string& name)
{
    Reader r(text, name);
    const std::unique_ptr<Element> doc = r.document();
    if (doc->name != "opencv_storage") {
        r.fail(doc->line,
               "expected <opencv_storage> as the root element, found <" + doc->name + ">");
    }
    const Element& cascade = need(*doc, "cascade", r);
    const std::string stageType = trimmed(need(cascade, "stageType", r).text);
    if (stageType != "BOOST") {
        r.fail(cascade.child("stageType")->line, "expected stageType BOOST, found " + stageType);
    }
    const std::string featureType = trimmed(need(cascade, "featureType", r).text);
    if (featureType != "HAAR") {
        r.fail(cascade.child("featureType")->line,
               "expected featureType HAAR, found " + featureType);
    }

    HaarCascade c;
    c.windowWidth = single<int>(cascade, "width", r);
    c.windowHeight = single<int>(cascade, "height", r);
    if (c.windowWidth < 3 || c.windowHeight < 3)
        r.fail(cascade.line, "window smaller than 3x3");
    // Bounded so the products the detector forms of window sizes (areas, scaled windows) stay
    // far inside 32 bits whatever the file says.
    if (c.windowWidth > kMaxWindow || c.windowHeight > kMaxWindow)
        r.fail(cascade.line, "window larger than " + std::to_string(kMaxWindow) + "x" +
                                 std::to_string(kMaxWindow));

    const Element& features = need(cascade, "features", r);
    for (const auto& f : features.children) {
        const Element& rects = need(*f, "rects", r);
        HaarFeature feature;
        for (const auto& re : rects.children) {
            if (feature.rectCount == 3)
                r.fail(re->line, "more than 3 rectangles in a feature");
            Numbers n(*re, r);
            HaarRect& hr = feature.rects[static_cast<std::size_t>(feature.rectCount++)];
            hr.x = n.next<int>();
            hr.y = n.next<int>();
            hr.width = n.next<int>();
            hr.height = n.next<int>();
            hr.weight = n.next<float>();
            if (!n.atEnd())
                r.fail(re->line, "expected 5 numbers (x y w h weight) in a rectangle");
            // Written so no sum can overflow, whatever the file holds.
            if (hr.x < 0 || hr.y < 0 || hr.width <= 0 || hr.height <= 0 ||
                hr.x > c.windowWidth || hr.y > c.windowHeight ||
                hr.width > c.windowWidth - hr.x || hr.height > c.windowHeight - hr.y) {
                r.fail(re->line, "rectangle outside the detection window");
            }
        }
        if (feature.rectCount < 2)
            r.fail(rects.line, "expected 2 or 3 rectangles in a feature");
        if (f->child("tilted") != nullptr)
            feature.tilted = single<int>(*f, "tilted", r) != 0;
        c.features.push_back(feature);
    }
    if (c.features.empty())
        r.fail(features.line, "expected at least one feature in <features>");
    const int featureCount = static_cast<int>(c.features.size());

    const Element& stages = need(cascade, "stages", r);
    for (const auto& s : stages.children) {
        HaarStage stage;
        stage.threshold = single<float>(*s, "stageThreshold", r);
        stage.firstWeak = static_cast<int>(c.weak.size());
        const Element& weakList = need(*s, "weakClassifiers", r);
        for (const auto& w : weakList.children) {
            const Element& nodesEl = need(*w, "internalNodes", r);
            const Element& leavesEl = need(*w, "leafValues", r);
            HaarWeakClassifier weak;
            weak.firstNode = static_cast<int>(c.nodes.size());
            weak.firstLeaf = static_cast<int>(c.leaves.size());
            Numbers nodes(nodesEl, r);
            while (!nodes.atEnd()) {
                HaarNode node;
                node.left = nodes.next<int>();
                node.right = nodes.next<int>();
                node.featureIndex = nodes.next<int>();
                node.threshold = nodes.next<float>();
                if (node.featureIndex < 0 || node.featureIndex >= featureCount) {
                    r.fail(nodesEl.line, "feature index out of range");
                }
                c.nodes.push_back(node);
                ++weak.nodeCount;
            }
            if (weak.nodeCount == 0)
                r.fail(nodesEl.line, "expected nodes in <internalNodes>");
            Numbers leaves(leavesEl, r);
            int leafCount = 0;
            while (!leaves.atEnd()) {
                c.leaves.push_back(leaves.next<float>());
                ++leafCount;
            }
            if (leafCount != weak.nodeCount + 1) {
                r.fail(leavesEl.line,
                       "expected " + std::to_string(weak.nodeCount + 1) + " leaf values");
            }
            for (int i = 0; i < weak.nodeCount; ++i) {
                const HaarNode& n = c.nodes[static_cast<std::size_t>(weak.firstNode + i)];
                for (const int child : {n.left, n.right}) {
                    // Children point forward (so evaluation terminates) or to a leaf.
                    if ((child > 0 && (child <= i || child >= weak.nodeCount)) ||
                        (child <= 0 && -child > weak.nodeCount)) {
                        r.fail(nodesEl.line, "node child index out of range");
                    }
                }
            }
            c.weak.push_back(weak);
            ++stage.weakCount;
        }
        if (stage.weakCount == 0)
            r.fail(weakList.line, "expected weak classifiers in a stage");
        c.stages.push_back(stage);
    }
    if (c.stages.empty())
        r.fail(stages.line, "expected at least one stage in <stages>");
    return c;
}

HaarCascade loadHaarCascade(const std::string& path)
{
    const BoundedFile file = readBoundedFile(path, limits::kCascadeBytes);
    if (file.status != BoundedFile::Status::Ok)
        throw std::runtime_error("cascade " + path + ": " + file.problem);
    return parseHaarCascade(file.text, path);
}

}  // namespace vision
