// A loadable module without the plug-in entry point: the loader must refuse it as "not a glintlab
// plug-in".
extern "C" __attribute__((visibility("default"))) int glintlab_not_a_plugin_marker() { return 42; }
