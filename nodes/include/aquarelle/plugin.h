/*
 * Aquarelle plugin ABI, version 1.
 *
 * This header is the whole contract between the host (the `aquarelle` executable, the editor,
 * the tests) and a plugin (a shared library holding one or more node types). It is plain C so
 * that a plugin built by another compiler, or against another release, either loads or is
 * refused with a clear message: nothing C++ crosses the boundary.
 *
 *   host                                plugin (.so)
 *   ----                                ------------
 *   dlopen(plugin)
 *   aquarelle_plugin_entry(ABI) ──────► returns aq_plugin_desc (static data)
 *   reads node descriptions             ports, params, flags: data, no side effects
 *   per node instance: create(host) ──► instance state (GL objects the node owns)
 *   per evaluation:    process(ctx) ──► binds inputs, draws through the host services
 *   destroy(instance)
 *
 * Rules:
 *  - Every GL call a plugin makes goes through functions loaded with host->get_proc_address
 *    (the C++ helper does this with glad). The host may switch context backends; when
 *    ctx->gl_generation changes the plugin must reload its GL functions.
 *  - A plugin keeps no GL state bound between calls (programs, framebuffers, textures).
 *  - Errors are values: process returns AQ_OK or AQ_ERROR after calling host->fail with a
 *    message that says what went wrong and how to fix it. Nothing is thrown across the ABI.
 *  - Structs carry struct_size so either side can grow them at the end without breaking the
 *    other; a change that is not append-only bumps AQ_ABI_VERSION.
 */
#ifndef AQUARELLE_PLUGIN_H
#define AQUARELLE_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define AQ_ABI_VERSION 1u
#define AQ_PLUGIN_ENTRY_NAME "aquarelle_plugin_entry"

#if defined(_WIN32)
#define AQ_PLUGIN_EXPORT __declspec(dllexport)
#else
#define AQ_PLUGIN_EXPORT __attribute__((visibility("default")))
#endif

enum { AQ_OK = 0, AQ_ERROR = 1 };

/* ---- Port and value types ------------------------------------------------------------ */

typedef enum aq_port_type {
  AQ_PORT_IMAGE = 1, /* a 2D texture */
  AQ_PORT_SCENE = 2  /* meshes, camera, light: CPU data (aq_scene) */
} aq_port_type;

enum {
  AQ_PORT_OPTIONAL = 1u << 0, /* an input that may stay unconnected */
  /* Appended in ABI 1: an input that takes any number of links (scene ports only), delivered
   * in order through aq_process_ctx::input_lists. A host that predates it refuses the plugin
   * (unknown flag), so a plugin using it never runs where the links would be lost. */
  AQ_PORT_MULTI = 1u << 1,
  /* Appended in ABI 1: an image input that reads values in [0, 1] only and for which 8 bits a
   * channel are enough (edge detection on a colour, a mask). When every reader of an output
   * says so, the host may store that output as AQ_FORMAT_RGBA8 ("bandwidth by need": llvmpipe
   * reads 8-bit texels about twice as fast as float ones); the plugin writing it asks for its
   * usual format and gets the narrower texture. Values outside [0, 1] clamp. An older host
   * refuses the plugin (unknown flag). */
  AQ_PORT_8BIT_ENOUGH = 1u << 2,
  /* Appended in ABI 1: an image port that handles AQ_FORMAT_RGBA8_HDR. On an input: the plugin
   * decodes it (aquarelle/hdr8.glsl) or only compares its values (min, max: the encoding is
   * monotone). On an output: the plugin writes it encoded when the host hands it such a
   * texture (the aq_image's format says so; the plugin asks for its usual format). The host
   * stores an output so only when its writer and every reader say AQ_PORT_HDR8, it is not the
   * requested output and the graph's precision is half. An older host refuses the plugin. */
  AQ_PORT_HDR8 = 1u << 3,
  /* Appended in ABI 1: an AQ_PORT_HDR8 image port that also handles AQ_FORMAT_RGBA8_HDR_BLOCKS
   * (a morphology chain keeps its images in 2 x 2 blocks between its nodes). The host stores
   * an output so only where it would store AQ_FORMAT_RGBA8_HDR and the writer and every reader
   * say AQ_PORT_BLOCKS. An older host refuses the plugin (unknown flag). */
  AQ_PORT_BLOCKS = 1u << 4,
  /* Appended in ABI 1: an AQ_PORT_BLOCKS port of a separable filter that can hand its last 1D
   * pass to its reader, or take its writer's last 1D pass over (aq_axis_pass): neighbourhood
   * fusion of a chain such as erode -> dilate -> erode, whose same-axis passes meet at the
   * nodes' boundaries and run as one. The host allows it on a link stored in blocks whose writer
   * says it on the output, whose only reader says it on the input, and whose output is not the
   * requested one (aq_host::may_defer_axis). An older host refuses the plugin (unknown flag). */
  AQ_PORT_DEFER_AXIS = 1u << 5
};

/* A 1D min or max pass along one axis that a writer left to its reader (AQ_PORT_DEFER_AXIS):
 * the output holds the writer's result before this pass. */
typedef struct aq_axis_pass {
  int32_t axis;   /* 0: along rows (x), 1: along columns (y) */
  int32_t dilate; /* 1: max, 0: min (per channel, of the stored 8-bit values) */
  int32_t radius; /* the window is 2 radius + 1 pixels, clamped to the image; 1..4 */
} aq_axis_pass;

typedef enum aq_format {
  AQ_FORMAT_RGBA16F = 1,
  AQ_FORMAT_RGBA32F = 2,
  AQ_FORMAT_R32F = 3,
  AQ_FORMAT_DEPTH32F = 4, /* depth attachment (shadow maps, z-buffers) */
  AQ_FORMAT_R32UI = 5,    /* integer ids */
  /* Appended in ABI 1: 8-bit unsigned normalised RGBA ([0, 1], steps of 1/255), filterable */
  AQ_FORMAT_RGBA8 = 6,
  /* Appended in ABI 1: linear HDR colour in an RGBA8 texture, rgb encoded per channel as
   * e = sqrt(c / (1 + c)) for c >= 0 (decode: c = e^2 / (1 - e^2)), alpha linear in [0, 1].
   * Monotone, so min and max work on the stored values; relative step about 2 % over
   * [0.1, 2]. Only ports that say AQ_PORT_HDR8 see it (bandwidth by need: llvmpipe reads
   * several 8-bit texels about three times as fast as float ones). GLSL: aquarelle/hdr8.glsl. */
  AQ_FORMAT_RGBA8_HDR = 7,
  /* Appended in ABI 1: an AQ_FORMAT_RGBA8_HDR image in 2 x 2 blocks of pixels: an RGBA32UI
   * texture of ceil(width / 2) x ceil(height / 2) texels (aq_image.width and height stay the
   * image's pixels), texel (i, j) holding the packUnorm4x8 words of pixels (2i, 2j) in x,
   * (2i + 1, 2j) in y, (2i, 2j + 1) in z and (2i + 1, 2j + 1) in w. A pass that works on whole
   * blocks (the morphology's) reads and writes four pixels per fragment. Only ports that say
   * AQ_PORT_BLOCKS see it; aq_image_texels() gives the texture's size. */
  AQ_FORMAT_RGBA8_HDR_BLOCKS = 8,
  /* Appended in ABI 1: four 32-bit unsigned words per pixel (RGBA32UI, nearest), packed data
   * whose layout the port that carries it states (gbuffer.surface: a deferred light's normal,
   * albedo and id in one texel, one read instead of three). Read back as the words' values. */
  AQ_FORMAT_RGBA32UI = 9
} aq_format;

typedef enum aq_precision { AQ_PRECISION_HALF = 0, AQ_PRECISION_FLOAT = 1 } aq_precision;

/* Appended in ABI 1: pixels [x0, x1) x [y0, y1) of an image, GL convention (row 0 at the
 * bottom): a part of an image that changed (aq_host::input_damage) or is drawn. */
typedef struct aq_rect {
  int32_t x0, y0, x1, y1;
} aq_rect;

typedef struct aq_image {
  uint32_t texture; /* GL texture name, GL_TEXTURE_2D, clamp-to-edge, linear filter */
  int32_t width;
  int32_t height;
  uint32_t format; /* aq_format */
} aq_image;

/* Appended in ABI 1: the size of an image's texture in texels: its pixels, or its 2 x 2
 * blocks for AQ_FORMAT_RGBA8_HDR_BLOCKS. */
static inline void aq_image_texels(const aq_image* image, int32_t* width, int32_t* height) {
  const int blocks = image->format == AQ_FORMAT_RGBA8_HDR_BLOCKS;
  *width = blocks ? (image->width + 1) / 2 : image->width;
  *height = blocks ? (image->height + 1) / 2 : image->height;
}

/* ---- Scenes: what flows on a `scene` port ------------------------------------------- */

typedef struct aq_mesh {
  const float* positions; /* xyz per vertex, object space */
  const float* normals;   /* xyz per vertex, unit length */
  const float* colors;    /* rgb per vertex, linear albedo */
  const uint32_t* indices;
  uint32_t vertex_count;
  uint32_t index_count; /* triangles: 3 indices each */
  float model[16];      /* object to world, column-major */
  uint32_t object_id;   /* >= 1; 0 means background */
  uint32_t flags;       /* reserved, 0 */
  /* Changes whenever the vertex data changes, so consumers re-upload only then. Unique
   * across meshes of one process. */
  uint64_t geometry_revision;
} aq_mesh;

typedef struct aq_camera {
  float position[3];
  float target[3];
  float up[3];
  float fov_y_degrees;
  float near_plane;
  float far_plane;
} aq_camera;

typedef struct aq_light {
  float direction[3]; /* direction the light travels (from the light into the scene), unit */
  float color[3];     /* linear */
  float ambient[3];   /* linear */
} aq_light;

/* Pixels a scene carries for its meshes (base colour textures), on the CPU like the vertices:
 * RGBA float, linear (working space), straight (not premultiplied) alpha, row 0 at v = 0. */
typedef struct aq_texture {
  const float* rgba; /* width * height * 4 floats; NULL: no texture */
  int32_t width;
  int32_t height;
  /* Changes whenever the pixels change, so consumers re-upload only then; unique per process. */
  uint64_t revision;
} aq_texture;

/* How a mesh's surface looks beyond its vertex colours (appended in ABI 1, one per mesh in
 * aq_scene::surfaces). albedo = vertex colour * texture(uv).rgb; texture alpha below
 * alpha_cutoff is a hole (cut-out cards: seaweed, plants) in the g-buffer and the shadow map. */
typedef struct aq_mesh_surface {
  const float* uvs;      /* uv per vertex (2 floats), or NULL */
  aq_texture base_color; /* rgba NULL: none (white) */
  float alpha_cutoff;    /* 0: opaque whatever the alpha */
  uint32_t flags;        /* reserved, 0 */
  /* Appended in ABI 1 (read only when aq_scene::surface_struct_size covers it; plugin.hpp's
   * aq::surface_art does, with the defaults below when absent or art_set is 0): the object's
   * art direction for the seed 002 (MNPR) passes. The control_map node turns it into images. */
  uint32_t art_set;        /* 1: the fields below are set; 0: use the defaults */
  float bleed;             /* bleeding amount [0, 1] (default 0) */
  float edge_darkening;    /* edge darkening amount [0, 4] (default 1) */
  float tremor;            /* hand tremor amplitude, world units (default 0) */
  float tremor_frequency;  /* hand tremor waves per world unit (default 4) */
  float fbm_density;       /* 0: amounts constant over the object, 1: fully FBM-modulated */
  float fbm_scale;         /* FBM lattice cells per object-space unit (default 2) */
} aq_mesh_surface;

typedef struct aq_scene {
  uint32_t struct_size;
  const aq_mesh* meshes;
  uint32_t mesh_count;
  aq_camera camera;
  aq_light light;
  float bounds_min[3]; /* world-space box holding every mesh */
  float bounds_max[3];
  double time; /* seconds */
  float water_height; /* world y of the water surface (caustic projection) */
  /* World units one period of the water's caustic pattern covers (the caustic texture's tile,
   * as cel_light projects it and as the caustics node sizes it). Appended in ABI 1: read it
   * only when struct_size covers it (plugin.hpp's aq::scene_caustic_tile does). */
  float caustic_tile;
  /* Appended in ABI 1 (read only when struct_size covers them; plugin.hpp's aq::scene_surface
   * and aq::scene_has_environment do): one surface per mesh, or NULL for none (untextured,
   * opaque), and the environment seen behind the scene, a vertical gradient from
   * environment_bottom (looking straight down) to environment_top (straight up), used when
   * has_environment is 1. surface_struct_size is sizeof(aq_mesh_surface) of the producer: the
   * array's stride, so the struct can grow at its end. (Not in aq_mesh: meshes travel as an
   * array without a size per element, so growing aq_mesh would break older readers.) */
  const aq_mesh_surface* surfaces;
  uint32_t surface_struct_size;
  uint32_t has_environment;
  float environment_top[3];
  float environment_bottom[3];
} aq_scene;

/* ---- Node descriptions: data the host reads without running anything ---------------- */

typedef struct aq_port_desc {
  const char* name;
  uint32_t type;  /* aq_port_type */
  uint32_t flags; /* AQ_PORT_* */
  const char* description;
} aq_port_desc;

typedef enum aq_param_type {
  AQ_PARAM_FLOAT = 1,
  AQ_PARAM_INT = 2,
  AQ_PARAM_BOOL = 3,
  AQ_PARAM_ENUM = 4,   /* value is an index into enum_values; files store the name */
  AQ_PARAM_STRING = 5,
  AQ_PARAM_PATH = 6,   /* a file path, resolved relative to the graph file */
  AQ_PARAM_COLOR = 7,  /* rgb, linear */
  AQ_PARAM_VEC3 = 8
} aq_param_type;

typedef struct aq_param_desc {
  const char* name;
  uint32_t type;         /* aq_param_type */
  double default_value[3]; /* float/int/bool/enum use [0]; color and vec3 use all three */
  double min_value;      /* range for float and int (and each component of vec3/color) */
  double max_value;
  double step;           /* UI hint: slider step, 0 for continuous */
  const char* default_string; /* string and path defaults; NULL for none */
  const char* enum_values;    /* "gaussian|strided": names for AQ_PARAM_ENUM */
  const char* ui_hint;        /* "slider", "log", "angle", "color", "file", or NULL */
  const char* description;
} aq_param_desc;

enum {
  AQ_NODE_TIME_DEPENDENT = 1u << 0, /* output changes with time: re-run every frame */
  AQ_NODE_POINTWISE = 1u << 1,      /* output pixel depends only on the same input pixel */
  /* Appended in ABI 1: the node's shaders may apply the host's epilogue to what they write to
   * output 0. The host prepends `vec4 aq_epilogue(vec4 colour)` to every fragment shader the
   * node compiles: the identity, or, when the pointwise chain that alone reads output 0 runs
   * inside this node's last pass (epilogue fusion), that chain's functions. A shader calls it
   * only on the value it writes to output 0 (the host refuses a draw into anything else). A
   * node that never calls it stays correct: the host then runs the chain as its own pass.
   * `vec4 aq_epilogue_at(vec4 colour, vec2 pixel)` applies it at another pixel centre of
   * output 0, for a shader that writes several pixels per fragment (2 x 2 blocks). */
  AQ_NODE_EPILOGUE = 1u << 2
};

struct aq_host;
struct aq_process_ctx;
struct aq_param_value;

/* A pointwise node's per-pixel function, so the host can fuse a chain of pointwise nodes (and
 * the resampling of a proxy render's output) into one pass instead of one pass per node, as
 * Blender's compositor does. The node's process() must compute the same function: the host
 * runs it whenever it does not fuse (e.g. when the node's own output is shown).
 *
 * `glsl` defines `vec4 AQ_APPLY(vec4 color, vec2 pixel, vec2 size)`: the output at the pixel
 * centre `pixel` (in pixels, gl_FragCoord convention) of an image of `size` pixels, from the
 * input colour there. Every uniform it declares is named `AQ_UNIFORM(name)`; the host defines
 * both macros differently for each fused node. It may #include "aquarelle/<lib>.glsl".
 * `set_uniforms` sets them on the bound `program`: the uniform AQ_UNIFORM(x) is named
 * prefix + "x". ctx is as for process(), with width and height those of the fused pass.
 * Returns AQ_OK, or AQ_ERROR after ctx->host->fail.
 * `color` is the node's first input at the pixel. Its other inputs (image ports only) are bound
 * by the host, before set_uniforms, as `uniform sampler2D AQ_UNIFORM(<port name>)`, readable
 * anywhere (edge reads its detection source 3x3); the host fuses such a node only when all of
 * them are connected (an unconnected one may stand for the first input's neighbourhood). */
typedef struct aq_pointwise_desc {
  uint32_t struct_size;
  const char* name; /* shown in compile errors, e.g. "tint.glsl" */
  const char* glsl;
  int (*set_uniforms)(void* instance, struct aq_process_ctx* ctx, uint32_t program,
                      const char* prefix);
  /* Appended in ABI 1 (read only when struct_size covers it): how far from the pixel, in
   * pixels, the function reads its other inputs (edge's 3x3 source: 1; 0 when it reads them at
   * the pixel only); -1 (and a desc without the field): anywhere. The host uses it to know which
   * pixels of a fused chain a change of those inputs reaches (aq_host::epilogue_damage). */
  int32_t reach;
} aq_pointwise_desc;

typedef struct aq_node_desc {
  uint32_t struct_size;
  const char* type_name; /* unique, [a-z0-9_]+ */
  const char* category;  /* "Scene", "Light", "Watercolor", "Filter", "Color", "Texture" */
  const char* description;
  uint32_t flags; /* AQ_NODE_* */
  const aq_port_desc* inputs;
  uint32_t input_count;
  const aq_port_desc* outputs;
  uint32_t output_count;
  const aq_param_desc* params;
  uint32_t param_count;
  /* Returns the node instance (may be NULL only on failure, after host->fail is impossible:
   * log instead). Called with a current GL context. */
  void* (*create)(const struct aq_host* host);
  void (*destroy)(void* instance);
  /* Runs the node. Returns AQ_OK, or AQ_ERROR after calling ctx->host->fail. */
  int (*process)(void* instance, struct aq_process_ctx* ctx);
  /* Appended in ABI 1: for AQ_NODE_POINTWISE nodes with one image input and one image output,
   * the per-pixel function the host may fuse; NULL: never fused. Read it only when
   * struct_size covers it. */
  const aq_pointwise_desc* pointwise;
  /* Appended in ABI 1: what `aquarelle validate` asks the node about its files (a mesh that is
   * not a mesh, a texture or material file it names that is missing), without a GL context
   * and without side effects; NULL: nothing to check. params are resolved as for process()
   * (paths against the graph file's folder). Each problem goes to report: level 0 an error
   * (the graph will not render), 1 a warning (it renders with a stand-in the message names);
   * param is the index of the parameter it is about. Read it only when struct_size covers it. */
  void (*check)(const struct aq_param_value* params, uint32_t param_count,
                void (*report)(void* data, int level, uint32_t param, const char* message),
                void* data);
} aq_node_desc;

typedef struct aq_plugin_desc {
  uint32_t abi_version; /* AQ_ABI_VERSION the plugin was built against */
  uint32_t struct_size;
  const char* plugin_name;
  const char* plugin_version;
  const aq_node_desc* const* nodes;
  uint32_t node_count;
} aq_plugin_desc;

/* The one symbol a plugin exports. host_abi_version lets a plugin refuse an older host. */
typedef const aq_plugin_desc* (*aq_plugin_entry_fn)(uint32_t host_abi_version);

/* ---- Evaluation --------------------------------------------------------------------- */

typedef struct aq_input_value {
  uint32_t type;      /* aq_port_type */
  uint32_t connected; /* 0 for an optional input left unconnected */
  aq_image image;     /* when type == AQ_PORT_IMAGE and connected */
  const aq_scene* scene; /* when type == AQ_PORT_SCENE and connected; owned by the producer */
} aq_input_value;

/* The links of one input (see aq_process_ctx::input_lists). */
typedef struct aq_input_list {
  const aq_input_value* values;
  uint32_t count; /* 0 when unconnected */
} aq_input_list;

typedef struct aq_param_value {
  double f[3];       /* float (f[0]), color, vec3 */
  int64_t i;         /* int, bool (0/1), enum index */
  const char* s;     /* string, path (already resolved against the graph file's folder) */
} aq_param_value;

typedef struct aq_shader_source {
  const char* name; /* file name shown in errors, e.g. "tint.frag" */
  const char* text; /* GLSL without #version; may `#include "aquarelle/<lib>.glsl"` */
  const char* path; /* absolute source path at build time, for hot reload; may be NULL */
} aq_shader_source;

typedef struct aq_process_ctx {
  uint32_t struct_size;
  const struct aq_host* host;
  void* host_data; /* pass back to every host call */
  const char* node_id;
  const aq_input_value* inputs; /* in description order */
  uint32_t input_count;
  const aq_param_value* params; /* in description order */
  uint32_t param_count;
  int32_t width; /* the resolution to render at: the graph's size times render_scale */
  int32_t height;
  uint32_t precision;      /* aq_precision */
  uint32_t working_format; /* AQ_FORMAT_RGBA16F or AQ_FORMAT_RGBA32F, from precision */
  double time;             /* seconds: (frame - first frame) / fps */
  int32_t frame;
  double fps;
  uint32_t gl_generation; /* changes when the GL context (and its functions) changed */
  uint32_t quality;       /* 0 draft, 1 preview, 2 final */
  /* Working pixels per output pixel (1 at quality final, less in proxy presets); width and
   * height are already scaled. A parameter measured in pixels (a blur radius, a displacement)
   * means output pixels: multiply it by render_scale. Appended in ABI 1: read it only when
   * struct_size covers it (plugin.hpp's Context::render_scale does). */
  double render_scale;
  /* Appended in ABI 1: every link of each input, in description order, in the order the graph
   * lists them (`"objects": ["a.object", "b.object"]`); inputs[i] is the first one. NULL when
   * no input of the node is AQ_PORT_MULTI. plugin.hpp's Context::link_count and input_scene(i,
   * k) read it. */
  const struct aq_input_list* input_lists;
  /* Appended in ABI 1: one key per input, in description order: equal keys mean the input holds
   * what it held on an earlier call (the host's key of its producer: type, parameters, inputs,
   * size, format and frame when time-dependent), so a node may keep what it derived from an
   * input while the key stays. 0 for an unconnected input and from hosts that do not set it
   * (then nothing may be assumed). plugin.hpp's Context::input_key reads it. */
  const uint64_t* input_keys;
} aq_process_ctx;

typedef struct aq_host {
  uint32_t abi_version;
  uint32_t struct_size;
  /* GL function lookup for the current context. */
  void* (*get_proc_address)(const char* name);
  /* Records an error for the node being processed; the message should say how to fix it. */
  void (*fail)(void* host_data, const char* message);
  void (*log)(void* host_data, int level /* 0 info, 1 warning */, const char* message);
  /* Compiles and links (cached by source; a program lives as long as the host). vertex may be
   * NULL for the host's full-screen triangle, which passes `in vec2 v_uv` (0..1) to the
   * fragment shader. Returns 0 on error, already reported with node, file and line. */
  uint32_t (*program)(void* host_data, const aq_shader_source* vertex,
                      const aq_shader_source* fragment);
  /* Allocates output `index` from the texture pool. */
  int (*output_image)(void* host_data, uint32_t index, int32_t width, int32_t height,
                      uint32_t format, aq_image* out);
  /* Makes output `index` the very texture of input `input_index` (a no-op node, no copy). */
  int (*pass_through)(void* host_data, uint32_t index, uint32_t input_index);
  /* Publishes a scene on output `index`; the data must stay valid until the next process or
   * destroy of this instance. */
  int (*output_scene)(void* host_data, uint32_t index, const aq_scene* scene);
  /* A scratch texture from the pool, returned to it when process returns. */
  int (*scratch_image)(void* host_data, int32_t width, int32_t height, uint32_t format,
                       aq_image* out);
  /* Binds a framebuffer with these colour attachments (and optional depth) and sets the
   * viewport to their size. */
  int (*bind_targets)(void* host_data, const aq_image* colors, uint32_t color_count,
                      const aq_image* depth);
  /* Draws the full-screen triangle into the bound targets with the bound program. */
  void (*draw_fullscreen)(void* host_data);
  /* Appended in ABI 1 (check struct_size): reads an image file through the host's image I/O
   * (OpenImageIO, converted to the working space through OpenColorIO; sRGB for 8-bit files
   * unless they say otherwise) and hands its pixels to `receive` (RGBA float, straight alpha,
   * row 0 at the bottom), valid only during that call. Returns AQ_OK, or AQ_ERROR with a
   * message in error[0..error_size) naming the path and the reason (nothing is recorded as
   * the node's failure: the caller decides whether it is a warning). */
  int (*read_image)(void* host_data, const char* path,
                    void (*receive)(void* user, const float* rgba, int32_t width, int32_t height),
                    void* user, char* error, size_t error_size);
  /* Appended in ABI 1 (check struct_size): after output_image(index, ...), 1 when the texture it
   * handed out is the very one this node instance's output `index` had on an earlier call and
   * nobody has written it since: it still holds what the node left in it, so the node may
   * update it in place (redraw only what changed). 0 otherwise: a texture of unknown content. */
  int (*output_kept)(void* host_data, uint32_t index);
  /* Appended in ABI 1 (check struct_size), damage tracking: a node whose outputs are kept
   * (output_kept) redraws only the pixels whose value can differ from what it left there.
   *
   * input_damage: where image input `input_index` may differ from what it held when this node
   * instance last ran: writes up to `capacity` disjoint rects and returns their count; 0: the
   * input did not change; -1: it may have changed anywhere (its writer did not say where, this
   * node's own parameters, size, format or time changed, it never ran, a scene input changed,
   * or more than `capacity` rects). */
  int (*input_damage)(void* host_data, uint32_t input_index, aq_rect* rects, uint32_t capacity);
  /* epilogue_damage: for a node running a fused epilogue (AQ_NODE_EPILOGUE), the pixels of
   * output 0 whose epilogue result may differ because the fused nodes' other inputs or
   * parameters changed; counts as input_damage. 0 without an epilogue. */
  int (*epilogue_damage)(void* host_data, aq_rect* rects, uint32_t capacity);
  /* set_output_damage: this call changed kept output `index` only inside these rects (every
   * other pixel holds what the node left there on its last call, and equals what drawing it
   * anew would give). Without it, the output counts as changed everywhere. For output 0 of a
   * node running an epilogue the rects must cover epilogue_damage's. Returns AQ_ERROR (after
   * failing the call) for an output that was not kept. */
  int (*set_output_damage)(void* host_data, uint32_t index, const aq_rect* rects, uint32_t count);
  /* set_draw_region: draw_fullscreen covers only these rects of the bound targets (scissored)
   * until the next set_draw_region or the end of process(); count 0: nothing; rects NULL: the
   * whole target again. A node running an epilogue still issues its epilogue draw when the
   * region is empty: it draws nothing, and tells the host the draw applies the epilogue (else
   * the host runs the fused nodes over the output as a pass of their own). */
  void (*set_draw_region)(void* host_data, const aq_rect* rects, uint32_t count);
  /* set_output_bounds: every pixel of output `index` outside these rects holds the output's
   * background (the value of a pixel nothing was drawn into: the g-buffer's id 0), as Nuke's
   * bounding box says. input_bounds: the rects the writer of image input `input_index` declared
   * for what it holds now; -1 when it declared none (anything may be anywhere) or more than
   * `capacity`. */
  int (*set_output_bounds)(void* host_data, uint32_t index, const aq_rect* rects, uint32_t count);
  int (*input_bounds)(void* host_data, uint32_t input_index, aq_rect* rects, uint32_t capacity);
  /* Appended in ABI 1 (check struct_size), neighbourhood fusion of separable filters
   * (AQ_PORT_DEFER_AXIS). may_defer_axis: 1 when output `index` may be left with its last 1D
   * pass undone for its one reader to run (the plan allows it: see AQ_PORT_DEFER_AXIS), else 0.
   * defer_axis: this call left that pass undone on output `index`; AQ_ERROR (after failing the
   * call) where may_defer_axis says 0. The host tells the reader (input_deferred_axis) as long
   * as the output holds this result. input_deferred_axis: 1 and the pass in `pass` when image
   * input `input_index` holds its writer's result before that pass, which this node must apply
   * first; 0 when the input is complete. */
  int (*may_defer_axis)(void* host_data, uint32_t index);
  int (*defer_axis)(void* host_data, uint32_t index, const aq_axis_pass* pass);
  int (*input_deferred_axis)(void* host_data, uint32_t input_index, aq_axis_pass* pass);
  /* Appended in ABI 1 (check struct_size): 1 when something reads output `index` in this
   * evaluation (a link of the plan, or the requested output: what a viewer shows), 0 when
   * nothing does. A node may then leave that output unwritten (the g-buffer skips its unread
   * targets); the host re-runs the node when the set of read outputs changes. */
  int (*output_read)(void* host_data, uint32_t index);
} aq_host;

#ifdef __cplusplus
}
#endif

#endif /* AQUARELLE_PLUGIN_H */
