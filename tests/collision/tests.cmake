graspsynth_test(collision/collision_scene_test.cpp LIBS graspsynth::collision)
