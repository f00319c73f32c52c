# Scene reading: parsing, validation and error messages; the format document against the key table.
bdl_add_test(test_scene SOURCES test_scene.c LABELS scene)
bdl_add_test(test_scene_docs SOURCES test_scene_docs.c LABELS scene)
