use bevy::prelude::*;
use passo_bevy::prelude::*;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, PassoPlugin::default().with_rate(60.0)))
        .add_systems(Startup, setup)
        .add_systems(Update, report_landings)
        .run();
}

fn setup(mut commands: Commands) {
    // One metre is 50 pixels.
    commands.spawn((Camera2d, Transform::from_scale(Vec3::splat(1.0 / 50.0))));
    commands.spawn((
        RigidBody::Static,
        Collider::rectangle(12.0, 1.0),
        Sprite::from_color(Color::srgb(0.4, 0.45, 0.5), Vec2::new(12.0, 1.0)),
        Transform::from_xyz(0.0, -4.0, 0.0),
    ));
    for i in 0..5 {
        commands.spawn((
            RigidBody::Dynamic,
            Collider::rectangle(0.8, 0.8),
            PhysicsMaterial {
                restitution: 0.3,
                ..default()
            },
            Sprite::from_color(Color::srgb(0.9, 0.6, 0.2), Vec2::splat(0.8)),
            TransformInterpolation,
            Transform::from_xyz(i as f32 - 2.0, 2.0 + i as f32, 0.0),
        ));
    }
}

fn report_landings(mut began: MessageReader<ContactBegan>) {
    for contact in began.read() {
        info!("{:?} touched {:?}", contact.entity_a, contact.entity_b);
    }
}
