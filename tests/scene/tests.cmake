# Tests of the scene module: objects, meshes, scenes and the rest pose.
graspsynth_test(scene/rest_pose_test.cpp LIBS graspsynth::scene)
graspsynth_test(scene/scene_model_test.cpp LIBS graspsynth::scene nlohmann_json::nlohmann_json)
graspsynth_test(scene/object_model_test.cpp LIBS graspsynth::scene nlohmann_json::nlohmann_json)
graspsynth_test(scene/triangle_mesh_test.cpp LIBS graspsynth::scene)
graspsynth_test(scene/base_frame_test.cpp LIBS graspsynth::scene)
